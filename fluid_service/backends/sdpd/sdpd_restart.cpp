// SPDX-License-Identifier: MIT
/// \file sdpd_restart.cpp
/// SdpdBackend: the particle state it reports and the state it saves and restores (bit-exact
/// restarts; the blob header and versioning are the fluid core's, state_blob.hpp).
#include <cmath>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/fluid/state_blob.hpp"
#include "sdpd_backend.hpp"

namespace sadr::fluid {

void SdpdBackend::write_state(ParticleState& out) const {
  out.dimension = model_.box.dimension;
  out.positions = y_.x;
  out.velocities = y_.v;
  out.densities = y_.rho;
  out.masses = mass_;
  out.kinds = kinds_;
  out.ids = ids_;
}

void SdpdBackend::save_state(BlobWriter& w) const {
  w.put(model_.seed);
  w.put(time_);
  w.put_vector(y_.x);
  w.put_vector(y_.v);
  w.put_vector(y_.rho);
  w.put<std::uint64_t>(y_.c.size());
  for (const auto& c : y_.c) w.put_vector(c);
  // The half-pair path sums in slab order, and slabs are assigned at list builds: restoring the
  // list at the same reference positions keeps restarts bit-exact.
  w.put_vector(list_ref_x_);
  if (open_.enabled()) open_.save(w, kinds_);  // version 3: kinds change at open boundaries
}

void SdpdBackend::restore_state(BlobReader& r, std::uint32_t version) {
  constexpr std::uint32_t kBlobVersionOpen = 3;
  if (version < 1 || version > kBlobVersionOpen) {
    throw InvalidArgument("restore: blob version " + std::to_string(version) +
                          " unsupported (this build reads 1, 2 and 3)");
  }
  if ((version == kBlobVersionOpen) != open_.enabled()) {
    throw InvalidArgument(std::string("restore: blob ") +
                          (open_.enabled()
                               ? "has no particle kinds but the model has an open boundary"
                               : "has particle kinds (open boundary) but the model has none"));
  }
  if (r.get<std::uint64_t>() != model_.seed)
    throw InvalidArgument("restore: blob seed differs from the model seed");
  const std::size_t n = mass_.size();
  Y y;
  const double t = r.get<double>();
  y.x = r.get_vector<double>(3 * n);
  y.v = r.get_vector<double>(3 * n);
  y.rho = r.get_vector<double>(n);
  const auto ns = r.get<std::uint64_t>();
  if (ns != y_.c.size())
    throw InvalidArgument("restore: blob has " + std::to_string(ns) + " species, model has " +
                          std::to_string(y_.c.size()));
  for (std::size_t s = 0; s < ns; ++s) y.c.push_back(r.get_vector<double>(n));
  std::vector<double> ref;
  if (version >= 2) {
    ref = r.get_vector<double>();
    if (!ref.empty() && ref.size() != 3 * n)
      throw InvalidArgument("restore: list reference positions have the wrong size");
  }
  OpenChannel::Saved open;
  if (version == kBlobVersionOpen) open = OpenChannel::read(r, wall_);
  r.expect_end();
  // Nothing non-finite is committed (fuzz_fluid_requests: an inf list reference
  // position reached the cell binning below as an out-of-range int conversion).
  auto require_finite = [](const std::vector<double>& a, const char* what) {
    for (std::size_t k = 0; k < a.size(); ++k) {
      if (!std::isfinite(a[k])) {
        throw InvalidArgument("restore: blob " + std::string(what) + "[" + std::to_string(k) +
                              "] = " + format_value(a[k]) + " (must be finite)");
      }
    }
  };
  if (!std::isfinite(t)) throw InvalidArgument("restore: blob time = " + format_value(t));
  require_finite(y.x, "positions");
  require_finite(y.v, "velocities");
  require_finite(y.rho, "densities");
  for (const auto& c : y.c) require_finite(c, "concentrations");
  require_finite(ref, "list reference positions");
  y_ = std::move(y);
  if (open_.enabled()) {
    open_.commit(std::move(open), kinds_);
    if (species_.has_reactions()) species_.update_sites(kinds_);
  }
  time_ = t;
  move_bodies(y_, time_);  // (the saved positions again, and the normals and references of t)
  prepared_ = false;
  list_ref_x_.clear();
  if (!ref.empty()) rebuild_neighbors(ref);
}

}  // namespace sadr::fluid
