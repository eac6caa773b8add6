// SPDX-License-Identifier: MIT
/// \file sdpd_open_boundary.cpp
/// OpenChannel (see sdpd_open_boundary.hpp).
#include "sdpd_open_boundary.hpp"

#include <algorithm>
#include <cmath>

#include "sadr/common/status.hpp"

namespace sadr::fluid {

void OpenChannel::setup(const FluidModel& model, const Kernel& kernel, const PeriodicBox& pbox,
                        const std::vector<double>& x, const std::vector<std::uint8_t>& wall,
                        std::vector<ParticleKind>& kinds) {
  enabled_ = model.open_boundary.enabled;
  ob_ = model.open_boundary;
  rho0_ = model.reference_density;
  dim_ = model.box.dimension;
  kernel_ = kernel;
  pbox_ = pbox;
  const std::size_t n = wall.size();
  buffer_.assign(n, 0);
  conveyor_.assign(n, 0);  // initial inlet particles are conveyor particles
  holes_.clear();
  for (std::size_t i = 0; i < n && enabled_; ++i) {
    const double s = x[3 * i + static_cast<std::size_t>(ob_.axis)];
    conveyor_[i] = !wall[i] && s < ob_.fluid_lo;
    if (!wall[i]) kinds[i] = s < ob_.fluid_lo ? ParticleKind::kInlet : ParticleKind::kFluid;
  }
}

// The inlet is a conveyor: its slots move with the inflow velocity; a conveyor particle entering
// the fluid leaves a hole one inlet length behind it (a hole reaching the fluid moves back by the
// same length). The outlet particles farthest downstream fill the holes (the hole farthest
// downstream first); with no outlet particle left a hole waits. An outlet particle past
// outlet_hi with no hole to fill is shifted back by outlet_hi - inlet_lo (an extra inlet
// particle, no slot). Kinds follow the position along the flow axis. Serial, in index order:
// independent of the thread count.
void OpenChannel::apply(double dt, OpenChannelFields f) {
  const auto& ob = ob_;
  const auto a = static_cast<std::size_t>(ob.axis);
  const std::size_t n = f.wall.size();
  const double lb_in = ob.fluid_lo - ob.inlet_lo;
  auto classify = [&](double s) {
    return s < ob.fluid_lo   ? ParticleKind::kInlet
           : s < ob.fluid_hi ? ParticleKind::kFluid
                             : ParticleKind::kOutlet;
  };
  for (std::size_t k = 0; k < holes_.size(); k += 3) {
    double* x = &holes_[k];
    x[a] += dt * ob.inflow_speed(x);
    if (x[a] >= ob.fluid_lo) x[a] -= lb_in;
  }
  outlets_.clear();
  bool past = false;
  for (std::size_t i = 0; i < n; ++i) {
    if (f.wall[i]) continue;
    const double* x = &f.x[3 * i];
    const ParticleKind k = classify(x[a]);
    if (f.kinds[i] == ParticleKind::kInlet && k != ParticleKind::kInlet && conveyor_[i]) {
      conveyor_[i] = 0;  // leaves a hole behind it
      holes_.insert(holes_.end(), {x[0], x[1], x[2]});
      holes_[holes_.size() - 3 + a] -= lb_in;
    }
    f.kinds[i] = k;
    if (k == ParticleKind::kOutlet) {
      outlets_.push_back(static_cast<std::uint32_t>(i));
      past = past || x[a] > ob.outlet_hi;
    }
  }
  if (!outlets_.empty() && (past || !holes_.empty())) {
    // outlet particles and holes, farthest downstream first (ties: lower index / older hole)
    std::sort(outlets_.begin(), outlets_.end(), [&](std::uint32_t p, std::uint32_t q) {
      const double xp = f.x[3 * p + a], xq = f.x[3 * q + a];
      return xp > xq || (xp == xq && p < q);
    });
    hole_order_.resize(holes_.size() / 3);
    for (std::size_t k = 0; k < hole_order_.size(); ++k)
      hole_order_[k] = static_cast<std::uint32_t>(k);
    std::stable_sort(hole_order_.begin(), hole_order_.end(), [&](std::uint32_t p, std::uint32_t q) {
      return holes_[3 * p + a] > holes_[3 * q + a];
    });
    const double shift = ob.outlet_hi - ob.inlet_lo;
    const std::size_t filled = std::min(outlets_.size(), hole_order_.size());
    for (std::size_t k = 0; k < outlets_.size(); ++k) {
      const std::uint32_t j = outlets_[k];
      if (k < filled) {
        for (int q = 0; q < 3; ++q) f.x[3 * j + q] = holes_[3 * hole_order_[k] + q];
        conveyor_[j] = 1;
        f.kinds[j] = ParticleKind::kInlet;
      } else if (f.x[3 * j + a] > ob.outlet_hi) {
        f.x[3 * j + a] -= shift;
        conveyor_[j] = 0;  // an extra inlet particle: it leaves no hole
        f.kinds[j] = ParticleKind::kInlet;
      } else {
        break;  // (sorted: the others are inside the outlet)
      }
    }
    if (filled > 0) {  // drop the filled holes, keep the others in creation order
      std::vector<std::uint8_t> gone(hole_order_.size(), 0);
      for (std::size_t k = 0; k < filled; ++k) gone[hole_order_[k]] = 1;
      std::size_t w = 0;
      for (std::size_t k = 0; k < gone.size(); ++k) {
        if (gone[k]) continue;
        for (int q = 0; q < 3; ++q) holes_[3 * w + q] = holes_[3 * k + q];
        ++w;
      }
      holes_.resize(3 * w);
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (f.wall[i]) continue;
    buffer_[i] = f.kinds[i] != ParticleKind::kFluid;
    if (f.kinds[i] == ParticleKind::kInlet) {  // prescribed velocity
      double* vi = &f.v[3 * i];
      vi[0] = vi[1] = vi[2] = 0.0;
      vi[a] = ob.inflow_speed(&f.x[3 * i]);
    } else if (f.kinds[i] == ParticleKind::kOutlet) {  // prescribed pressure P = 0
      f.rho[i] = rho0_;
    }
  }
  // Zero-gradient values from the fluid (Lastiwka et al. 2009: a subsonic inlet takes one
  // quantity from inside, the pressure; a subsonic outlet everything but the pressure): the
  // density of an inlet particle and the velocity of an outlet particle are the Shepard average,
  // over the fluid particles within one kernel support of the buffer's face, weighted by the
  // kernel of the cross-flow distance (so d/d(axis) = 0 across the buffer).
  const double h = kernel_.support();
  extrapolate_from_fluid(ParticleKind::kInlet, ob.fluid_lo, ob.fluid_lo + h, f);
  extrapolate_from_fluid(ParticleKind::kOutlet, ob.fluid_hi - h, ob.fluid_hi, f);
}

void OpenChannel::extrapolate_from_fluid(ParticleKind target, double lo, double hi,
                                         OpenChannelFields& f) {
  const auto a = static_cast<std::size_t>(ob_.axis);
  const std::size_t n = f.wall.size();
  const double h = kernel_.support(), h2 = h * h;
  face_fluid_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const double s = f.x[3 * i + a];
    if (f.kinds[i] == ParticleKind::kFluid && s >= lo && s < hi)
      face_fluid_.push_back(static_cast<std::uint32_t>(i));
  }
  const bool velocity = target == ParticleKind::kOutlet;
  for (std::size_t i = 0; i < n; ++i) {
    if (f.kinds[i] != target) continue;
    double wsum = 0, v[3] = {0, 0, 0}, rho = 0;
    for (const std::uint32_t j : face_fluid_) {
      double d[3] = {0, 0, 0};
      for (int c = 0; c < dim_; ++c) {
        if (c != ob_.axis) d[c] = f.x[3 * i + c] - f.x[3 * j + c];
      }
      pbox_.minimum_image(d);
      const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
      if (r2 >= h2) continue;
      const double w = kernel_.w(std::sqrt(r2)) * f.mass[j] / f.rho[j];
      wsum += w;
      for (int c = 0; c < 3; ++c) v[c] += w * f.v[3 * j + c];
      rho += w * f.rho[j];
    }
    if (!(wsum > 0)) continue;  // no fluid across from it: keeps its values
    if (velocity) {
      for (int c = 0; c < 3; ++c) f.v[3 * i + c] = v[c] / wsum;
    } else {
      f.rho[i] = rho / wsum;
    }
  }
}

void OpenChannel::save(BlobWriter& w, const std::vector<ParticleKind>& kinds) const {
  std::vector<std::uint8_t> k(kinds.size());
  for (std::size_t i = 0; i < k.size(); ++i) k[i] = static_cast<std::uint8_t>(kinds[i]);
  w.put_vector(k);
  w.put_vector(conveyor_);
  w.put_vector(holes_);
}

OpenChannel::Saved OpenChannel::read(BlobReader& r, const std::vector<std::uint8_t>& wall) {
  const std::size_t n = wall.size();
  Saved s;
  const auto k = r.get_vector<std::uint8_t>(n);
  s.kinds.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const bool wall_k = k[i] == static_cast<std::uint8_t>(ParticleKind::kWall);
    if (k[i] > 3 || wall_k != (wall[i] != 0))
      throw InvalidArgument("restore: particle kinds do not match the model's wall particles");
    s.kinds[i] = static_cast<ParticleKind>(k[i]);
  }
  s.conveyor = r.get_vector<std::uint8_t>(n);
  s.holes = r.get_vector<double>();
  if (s.holes.size() % 3 != 0) throw InvalidArgument("restore: inlet holes have the wrong size");
  return s;
}

void OpenChannel::commit(Saved&& s, std::vector<ParticleKind>& kinds) {
  kinds = std::move(s.kinds);
  conveyor_ = std::move(s.conveyor);
  holes_ = std::move(s.holes);
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    buffer_[i] = kinds[i] == ParticleKind::kInlet || kinds[i] == ParticleKind::kOutlet;
  }
}

std::size_t OpenChannel::bytes() const {
  return buffer_.capacity() + conveyor_.capacity() + holes_.capacity() * sizeof(double) +
         (face_fluid_.capacity() + hole_order_.capacity() + outlets_.capacity()) *
             sizeof(std::uint32_t);
}

}  // namespace sadr::fluid
