// SPDX-License-Identifier: MIT
// Cost of the hot-path rate laws against mass action (issue #17):
//  - SSA: ns per propensity evaluation, ReactionTable::propensity (what every event
//    and every rate update of a voxel calls per reaction), over 4096 voxels;
//  - transport: ns per particle and reaction, SpeciesTransport::add_reactions (the
//    deterministic reaction term of every particle at every sub-step stage).
// Laws: mass action A + B -> C, Michaelis-Menten, Hill (n = 2.5: a pow), and the
// expression "kcat*B*A/(Km+A)". Prints one JSON object per line.
// Run (quiet machine): build/release/bench/rate_law/rate_law_bench [--reps N]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "sadr/fluid/species_transport.hpp"
#include "sadr/ssa/rdme_state.hpp"

namespace {

using Clock = std::chrono::steady_clock;

struct Case {
  const char* name;
  std::optional<sadr::rate_law::Definition> law;
};

std::vector<Case> cases() {
  using sadr::rate_law::Definition;
  using sadr::rate_law::Type;
  Definition mm;
  mm.type = Type::kMichaelisMenten;
  mm.kcat = 2;
  mm.km = 0.5;
  mm.substrate = std::string("A");
  mm.catalyst = std::string("B");
  Definition hill;
  hill.type = Type::kHill;
  hill.vmax = 3;
  hill.half = 1;
  hill.n = 2.5;
  hill.of = std::string("A");
  Definition ex;
  ex.type = Type::kExpression;
  ex.expression = std::string("kcat*B*A/(Km+A)");
  ex.parameters = {{"kcat", 2.0}, {"Km", 0.5}};
  return {
      {"mass_action", std::nullopt}, {"michaelis_menten", mm}, {"hill", hill}, {"expression", ex}};
}

constexpr int kSide = 64;  // 64 x 64 = 4096 particles

double ssa_ns(const Case& c, int reps) {
  using namespace sadr::ssa;
  Model m;
  m.species = {{"A", 0}, {"B", 0}, {"C", 0}};
  Reaction rx;
  rx.def.name = "r";
  rx.reactants = c.law ? std::vector<std::pair<int, int>>{{0, 1}}
                       : std::vector<std::pair<int, int>>{{0, 1}, {1, 1}};
  rx.products = {{2, 1}};
  rx.def.rate = 0.1;
  rx.def.law = c.law;
  m.reactions = {rx};
  m.box.dimension = 2;
  m.box.hi = {kSide * 1.0, kSide * 1.0, 1.0};
  m.box.periodic = {true, true, false};
  m.smoothing_length = 1.5;
  sadr::ParticleState p;
  p.dimension = 2;
  p.resize(kSide * kSide, false);
  for (int i = 0; i < kSide * kSide; ++i) {
    p.positions[3 * i] = (i % kSide) + 0.5;
    p.positions[3 * i + 1] = (i / kSide) + 0.5;
    p.masses[i] = p.densities[i] = 1.0;
  }
  RdmeState s(m);
  s.update_graph(p);
  std::vector<std::int64_t> a(p.size()), b(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) a[i] = 1 + i % 50, b[i] = 1 + i % 7;
  s.set_counts(0, a);
  s.set_counts(1, b);
  const ReactionTable& t = s.reactions();
  const std::int64_t* x = s.all_counts().data();
  const std::size_t n = p.size();
  double sink = 0;
  const auto t0 = Clock::now();
  for (int r = 0; r < reps; ++r) {
    for (std::uint32_t i = 0; i < n; ++i) sink += t.propensity(0, i, x, n);
  }
  const double ns = std::chrono::duration<double, std::nano>(Clock::now() - t0).count();
  if (sink == 42.4242) std::puts("");  // keeps the loop
  return ns / (static_cast<double>(reps) * static_cast<double>(n));
}

double transport_ns(const Case& c, int reps) {
  using namespace sadr::fluid;
  FluidModel m;
  m.species.push_back({"A", 0.0, true, {}, {}});
  m.species.push_back({"B", 0.0, true, {}, {}});
  m.species.push_back({"C", 0.0, true, {}, {}});
  ReactionSpec rx;
  rx.def.name = "r";
  rx.reactants = c.law ? std::vector<std::pair<int, int>>{{0, 1}}
                       : std::vector<std::pair<int, int>>{{0, 1}, {1, 1}};
  rx.products = {{2, 1}};
  rx.def.rate = 0.1;
  rx.def.law = c.law;
  m.reactions = {rx};
  sadr::ParticleState p;
  p.dimension = 2;
  p.resize(kSide * kSide, false);
  for (std::size_t i = 0; i < p.size(); ++i) p.masses[i] = p.densities[i] = 1.0;
  SpeciesTransport st;
  st.setup(m, p);
  std::vector<std::vector<double>> conc(3, std::vector<double>(p.size()));
  for (std::size_t i = 0; i < p.size(); ++i) {
    conc[0][i] = 0.1 + 0.01 * (i % 50);
    conc[1][i] = 0.5 + 0.1 * (i % 7);
  }
  std::vector<std::vector<double>> dc(3, std::vector<double>(p.size(), 0.0));
  const auto t0 = Clock::now();
  for (int r = 0; r < reps; ++r) {
    for (std::size_t i = 0; i < p.size(); ++i) st.add_reactions(i, conc, dc);
  }
  const double ns = std::chrono::duration<double, std::nano>(Clock::now() - t0).count();
  if (dc[2][0] == 42.4242) std::puts("");
  return ns / (static_cast<double>(reps) * static_cast<double>(p.size()));
}

}  // namespace

int main(int argc, char** argv) {
  int reps = 2000;
  for (int k = 1; k + 1 < argc; ++k) {
    if (std::string(argv[k]) == "--reps") reps = std::atoi(argv[k + 1]);
  }
  double base_ssa = 0, base_tr = 0;
  for (const Case& c : cases()) {
    const double s = ssa_ns(c, reps), t = transport_ns(c, reps);
    if (!c.law) base_ssa = s, base_tr = t;
    std::printf(
        "{\"law\": \"%s\", \"ssa_ns_per_propensity\": %.2f, \"ssa_vs_mass_action\": %.2f, "
        "\"transport_ns_per_particle_reaction\": %.2f, \"transport_vs_mass_action\": %.2f}\n",
        c.name, s, s / base_ssa, t, t / base_tr);
  }
  return 0;
}
