// SPDX-License-Identifier: MIT
// ssa_service and hybrid reactions (docs/method.md section 4c): an Advance of a
// model with frozen species must carry their concentrations, one per particle;
// otherwise it is refused naming the species, before any event.
#include <gtest/gtest.h>

#include <string>

#include "sadr/common/status.hpp"
#include "sadr/ssa/ssa_service.hpp"
#include "sadr/wire/convert.hpp"
#include "service_probe.hpp"

namespace sadr::ssa {
namespace {

using testing::Probe;

v1::SsaRequest init_request() {
  v1::SsaRequest r;
  auto* init = r.mutable_init();
  auto* m = init->mutable_model();
  testing::set_line_box(*m, 2.0, true);
  m->set_smoothing_length(0.5);
  const std::string a = "A", b = "B";
  auto* species = m->add_species();
  species->set_name(a);
  species->set_stochastic(true);
  m->add_frozen_species(b);
  auto* rx = m->add_reactions();
  rx->set_name("birth");
  rx->add_products()->set_species("A");
  rx->mutable_products(0)->set_count(1);
  rate_law::Definition d;
  d.type = rate_law::Type::kExpression;
  d.expression = "2*B";
  wire::to_proto(d, *rx->mutable_law());
  ParticleState p;
  p.dimension = 1;
  p.resize(2, false);
  for (std::size_t i = 0; i < 2; ++i) {
    p.positions[3 * i] = 0.5 + static_cast<double>(i);
    p.masses[i] = 1.0;
    p.densities[i] = 1.0;
  }
  wire::to_proto(p, *init->mutable_particles(), false);
  return r;
}

std::string advance_error(Probe& h, int values) {
  v1::SsaRequest r;
  auto* a = r.mutable_advance();
  a->set_run_id("x");
  a->set_step_index(0);
  a->set_t_end(1.0);
  if (values >= 0) {
    auto* f = a->mutable_frozen()->add_species();
    f->set_name("B");
    for (int k = 0; k < values; ++k) f->add_concentrations(1.0);
  }
  v1::SsaReply reply;
  try {
    h.call(r, reply);
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "no error";
}

TEST(SsaFrozen, AnAdvanceWithoutTheFrozenConcentrationsIsRefusedNamingTheSpecies) {
  Probe h;
  v1::SsaReply reply;
  h.call(init_request(), reply);
  EXPECT_NE(advance_error(h, -1).find("concentrations of the deterministic species 'B' (read by "
                                      "a hybrid reaction's law) are missing"),
            std::string::npos);
  EXPECT_NE(advance_error(h, 1).find("are 1 values; required: one per particle (2)"),
            std::string::npos);
  EXPECT_EQ(advance_error(h, 2), "no error");
}

}  // namespace
}  // namespace sadr::ssa
