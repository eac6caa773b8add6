// SPDX-License-Identifier: MIT
// Unit: the registry, model validation and bad-input / stability / blow-up errors.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

#include "fluid_test_scenes.hpp"
#include "sadr/common/status.hpp"
#include "sadr/fluid/builtin_backends.hpp"

namespace sadr::fluid {
namespace {

using test::LatticeSpec;

BackendRegistry builtin() {
  BackendRegistry r;
  register_builtin_backends(r);
  return r;
}

FluidModel small_model(ParticleState& p) {
  LatticeSpec s;
  s.dimension = 2;
  s.n = {8, 8, 1};
  s.dx = 0.1;
  FluidModel m;
  p = test::make_lattice(s, m.box);
  p.masses.assign(p.size(), 0.01);
  m.smoothing_length = 0.3;
  m.reference_density = 1.0;
  m.sound_speed = 1.0;
  m.shear_viscosity = 0.01;
  return m;
}

TEST(Registry, BuiltinNamesAndCreation) {
  const auto r = builtin();
  EXPECT_EQ(r.names(), (std::vector<std::string>{"prescribed", "sdpd", "static", "tdpd"}));
  EXPECT_EQ(r.create("sdpd")->name(), "sdpd");
  EXPECT_EQ(r.create("static")->name(), "static");
  EXPECT_TRUE(r.create("sdpd")->capabilities().moves_particles);
  EXPECT_FALSE(r.create("static")->capabilities().moves_particles);
}

TEST(Registry, UnknownNameListsKnownOnes) {
  const auto r = builtin();
  try {
    (void)r.create("lbm");
    FAIL() << "expected InvalidArgument";
  } catch (const InvalidArgument& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("lbm"), std::string::npos);
    EXPECT_NE(msg.find("prescribed, sdpd, static, tdpd"), std::string::npos) << msg;
  }
}

TEST(Registry, DuplicateAndEmptyRejected) {
  auto r = builtin();
  EXPECT_THROW(r.add("sdpd", [] { return std::unique_ptr<FluidBackend>{}; }), InvalidArgument);
  EXPECT_THROW(r.add("", [] { return std::unique_ptr<FluidBackend>{}; }), InvalidArgument);
}

TEST(ModelValidation, ReportsEveryProblemWithFieldAndValue) {
  FluidModel m;
  m.smoothing_length = -1;
  m.shear_viscosity = -2;
  m.kernel = "gauss";
  m.species.push_back({"A", -0.5, true, {}, {}});
  m.reactions.push_back({"r", {{3, 1}}, {}, 1.0, {}, {}});
  try {
    m.validate();
    FAIL();
  } catch (const InvalidArgument& e) {
    const std::string msg = e.what();
    for (const char* field : {"smoothing_length = -1", "shear_viscosity = -2", "gauss",
                              "species[0].diffusivity", "reactions[0].reactants species"}) {
      EXPECT_NE(msg.find(field), std::string::npos) << field << " missing in: " << msg;
    }
  }
}

TEST(BackendErrors, CallsBeforeInitializeFail) {
  for (const char* name : {"sdpd", "static"}) {
    auto b = builtin().create(name);
    EXPECT_THROW(b->advance(0, 0.1), FailedPrecondition) << name;
    EXPECT_THROW((void)b->save(), FailedPrecondition) << name;
  }
}

TEST(BackendErrors, BadInitialStateAndConcentrations) {
  ParticleState p;
  FluidModel m = small_model(p);
  auto b = builtin().create("sdpd");
  ParticleState wrong_dim = p;
  wrong_dim.dimension = 3;
  EXPECT_THROW(b->initialize(m, wrong_dim, {}), InvalidArgument);
  m.species.push_back({"A", 0.1, true, {}, {}});
  EXPECT_THROW(b->initialize(m, p, {std::vector<double>(3, 0.0)}), InvalidArgument);
  ParticleState neg = p;
  neg.masses[5] = -1;
  EXPECT_THROW(b->initialize(m, neg, {}), InvalidArgument);
  b->initialize(m, p, {});
  EXPECT_THROW(b->advance(0, -1.0), InvalidArgument);
  EXPECT_THROW(b->set_concentrations(0, std::vector<double>(2, 0.0)), InvalidArgument);
  EXPECT_THROW((void)b->concentrations(1), InvalidArgument);
  EXPECT_THROW(b->restore("garbage"), InvalidArgument);
}

// max_time_step above the acoustic limit is an upper bound that does not bind: the sub-steps and
// the state are those of the automatic rule (the old rule refused the advance).
TEST(Stability, MaxTimeStepAboveTheLimitLeavesTheSubstepsToTheLimit) {
  ParticleState p;
  FluidModel m = small_model(p);
  m.max_time_step = 0;  // automatic: splits into sub-steps
  auto automatic = builtin().create("sdpd");
  automatic->initialize(m, p, {});
  const auto rep = automatic->advance(0, 1.0);
  EXPECT_EQ(rep.limiting_criterion, "acoustic");
  EXPECT_NEAR(rep.stable_dt, 0.0375, 1e-12);
  EXPECT_EQ(rep.substeps, 27u);  // ceil(1 / 0.0375)
  EXPECT_NEAR(rep.time, 1.0, 1e-12);
  m.max_time_step = 1.0;  // acoustic limit is 0.25 * 0.15 / 1 = 0.0375
  auto capped = builtin().create("sdpd");
  capped->initialize(m, p, {});
  const auto rep1 = capped->advance(0, 1.0);
  EXPECT_EQ(rep1.substeps, 27u);
  ParticleState a, b;
  automatic->read_state(a);
  capped->read_state(b);
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.velocities, b.velocities);
  m.max_time_step = 0.02;  // below the limit: it binds
  auto fine = builtin().create("sdpd");
  fine->initialize(m, p, {});
  EXPECT_EQ(fine->advance(0, 1.0).substeps, 50u);
}

TEST(Stability, BlowUpIsDiagnosed) {
  ParticleState p;
  FluidModel m = small_model(p);
  p.velocities[3 * 10] = 50.0;  // a violent kick with a forced, far too large step
  m.max_time_step = 0.5;
  m.force_time_step = true;
  auto b = builtin().create("sdpd");
  b->initialize(m, p, {});
  try {
    for (std::uint64_t s = 0; s < 20; ++s) b->advance(s, 0.5);
    FAIL() << "expected NumericalFailure";
  } catch (const NumericalFailure& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("particle id"), std::string::npos) << msg;
    // The fluid core's report: step, sub-step, particle id, field, its value and the limit.
    std::map<std::string, std::string> d(e.details().begin(), e.details().end());
    for (const char* k : {"step", "substep", "particle_id", "field", "value", "limit"})
      EXPECT_TRUE(d.contains(k)) << k << " missing in: " << msg;
    EXPECT_NE(msg.find(d["field"] + " = " + d["value"] + " (" + d["limit"] + ")"),
              std::string::npos)
        << msg;
  }
}

// The blob header is the core's: another backend's blob, a foreign blob and an unknown header
// format are refused by name; a state blob starts with the format-1 header.
TEST(BackendSeam, BlobHeaderNamesTheBackend) {
  ParticleState p;
  FluidModel m = small_model(p);
  m.species.push_back({"A", 0.01, true, {}, {}});
  auto sdpd = builtin().create("sdpd");
  auto st = builtin().create("static");
  sdpd->initialize(m, p, {});
  st->initialize(m, p, {});
  const std::string blob = sdpd->save();
  EXPECT_EQ(blob.substr(8, 16), "sadr.fluid.state");
  try {
    st->restore(blob);
    FAIL() << "expected InvalidArgument";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("written by backend 'sdpd', not 'static'"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(st->restore(std::string(40, 'x')), InvalidArgument);
  std::string bad = st->save();
  bad[24] = 7;  // header format 7
  try {
    st->restore(bad);
    FAIL() << "expected InvalidArgument";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("header format 7"), std::string::npos) << e.what();
  }
  st->restore(st->save());  // (and the refusals left it usable)
}

// Initial-state checks are the core's, the same for every backend: a non-finite initial
// concentration is refused by static and tdpd as by sdpd, naming species, particle and value.
TEST(BackendSeam, EveryBackendRefusesANonFiniteConcentration) {
  ParticleState p;
  FluidModel m = small_model(p);
  m.species.push_back({"A", 0.01, true, {}, {}});
  std::vector<std::vector<double>> c{std::vector<double>(p.size(), 1.0)};
  c[0][5] = std::nan("");
  for (const char* name : {"sdpd", "static", "tdpd"}) {
    auto b = builtin().create(name);
    try {
      b->initialize(m, p, c);
      FAIL() << name << ": expected InvalidArgument";
    } catch (const InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find(std::string(name) + ": concentrations[0][5] = nan"),
                std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace sadr::fluid

namespace sadr::fluid {
namespace {

// c_0 is optional in the model (static scenes have no equation of state) but
// sdpd refuses to start without it, naming the field.
TEST(SoundSpeed, OptionalForStaticRequiredForSdpd) {
  ParticleState p;
  FluidModel m = small_model(p);
  m.sound_speed = 0.0;
  EXPECT_NO_THROW(m.validate());
  EXPECT_NO_THROW(builtin().create("static")->initialize(m, p, {}));
  try {
    builtin().create("sdpd")->initialize(m, p, {});
    FAIL() << "sdpd must refuse c_0 = 0";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("sdpd: sound_speed = 0 (must be > 0"), std::string::npos)
        << e.what();
  }
  m.sound_speed = -1.0;
  EXPECT_THROW(m.validate(), InvalidArgument);
}

}  // namespace
}  // namespace sadr::fluid
