// SPDX-License-Identifier: MIT
// Stochastic chemistry on a domain made by the `geometry` section, end to end: a first-order
// RDME (production 0 -> A at rate b in the region body `source`, decay A -> 0 at rate k
// everywhere, diffusion kappa) in a closed 2D ellipse with a solid disk as a hole, static fluid,
// run as an ensemble by `sadr run -r R`. The per-particle ensemble mean and variance of
// `ensemble/frame_*.csv` at three times are compared with the exact solution on the same
// particle graph: the graph is built by the SSA library from the particles the scene loader
// makes (those `sadr geometry` writes), dumped with graph_to_json (walls no-flux) and solved by
// tests/ssa/linear_rdme_reference.py (scipy). From zero, X_i(t) is Poisson(lambda_i(t))
// (Jahnke & Huisinga 2007): mean = variance = lambda_i, 4th central moment lambda + 3
// lambda^2. z-tests of the mean and the variance per particle with lambda_i >= 0.05, Bonferroni
// over all of them at a family-wise false-failure rate of 1e-3, and per time a chi-square test
// of the sum of the squared mean z (1e-3 each): false-failure rate at most 4e-3 in all.
#include <gtest/gtest.h>

#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli_test_support.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "sadr/ssa/graph_json.hpp"
#include "sadr/ssa/nsm_solver.hpp"

namespace sadr::e2e {
namespace {

const std::string kScene = R"yaml(name: geometry_rdme
dimension: 2
box: {lower: [-0.2, -0.1], upper: [2.2, 1.5]}
geometry:
  spacing: 0.1
  bodies:
    - {name: tank, role: fluid, shape: {type: ellipse, center: [1.0, 0.7], radii: [1.0, 0.6]}}
    - {name: hole, role: solid, shape: {type: disk, center: [1.3, 0.7], radius: 0.2}}
    - {name: source, role: region, shape: {type: disk, center: [0.45, 0.7], radius: 0.2}}
fluid: {backend: static, h_over_dx: 2.0}
species:
  - {name: A, diffusivity: 0.02}
reactions:
  - {name: production, equation: "0 -> A", rate: 200.0, regions: [source]}
  - {name: decay, equation: "A -> 0", rate: 0.5}
time: {coupling_step: 0.5, end: 6.0}
output: {times: [0.5, 2.0, 6.0], formats: [csv]}
seed: 11
)yaml";

constexpr double kKappa = 0.02, kDecay = 0.5, kBirth = 200.0;

/// Rows of a CSV with a header line: column name -> values.
std::map<std::string, std::vector<double>> read_columns(const fs::path& p) {
  std::ifstream in(p);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  {
    std::stringstream ss(line);
    std::string n;
    while (std::getline(ss, n, ',')) names.push_back(n);
  }
  std::map<std::string, std::vector<double>> out;
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string v;
    for (std::size_t k = 0; k < names.size() && std::getline(ss, v, ','); ++k) {
      out[names[k]].push_back(v.empty() ? NAN : std::stod(v));
    }
  }
  return out;
}

int realizations() {
  const char* e = std::getenv("SADR_GEOMETRY_RDME_REALIZATIONS");
  return e ? std::atoi(e) : 1000;
}

TEST(GeometryRdmeValidation, EnsembleMeanAndVarianceMatchTheExactRdmeOnTheGeneratedGraph) {
  ASSERT_EQ(std::system("/usr/bin/python3 -c 'import scipy' > /dev/null 2>&1"), 0)
      << "needs /usr/bin/python3 with scipy (deploy/install-deps.sh installs python3-scipy)";
  const int r_count = realizations();
  const fs::path d = scratch("geometry-rdme");
  const fs::path scene = write_scene(d, kScene);
  const std::string cmd = bin("sadr") + " run " + scene.string() + " -q --embedded -r " +
                          std::to_string(r_count) + " -j 1 -o " + (d / "out").string();
  ASSERT_EQ(run(cmd, d / "run.log"), 0) << read_file(d / "run.log");

  // The exact solution on the graph of the loader's particles.
  const orchestrator::Scene s = orchestrator::load_scene(scene);
  ssa::Model model;
  model.species = {{"A", kKappa}};
  model.box = s.box;
  model.smoothing_length = s.fluid.smoothing_length;
  model.regularization = s.ssa.regularization;
  ssa::NsmSolver solver(model, 1);
  solver.update_graph(s.particles);
  const ssa::DiffusionGraph& graph = solver.graph();
  const std::size_t n = s.particles.size();
  const orchestrator::Region* source = s.find_region("source");
  ASSERT_NE(source, nullptr);
  ssa::LinearRdmeSpec spec;
  spec.kappa = kKappa;
  spec.decay = kDecay;
  spec.birth.assign(n, 0.0);
  std::size_t producing = 0;
  for (const auto i : source->particles) {
    if (s.particles.kind(i) != ParticleKind::kFluid) continue;
    spec.birth[i] = kBirth * graph.volume[i];
    ++producing;
  }
  spec.x0.assign(n, 0);
  spec.times = {0.5, 2.0, 6.0};
  spec.variance = true;
  spec.include_wall_edges = false;
  const fs::path json = d / "graph.json", ref = d / "exact.csv";
  std::ofstream(json) << ssa::graph_to_json(graph, spec);
  const std::string py = std::string("/usr/bin/python3 ") + SADR_SOURCE_DIR +
                         "/tests/ssa/linear_rdme_reference.py " + json.string() + " --out " +
                         ref.string();
  ASSERT_EQ(std::system(py.c_str()), 0) << py;
  const auto exact = read_columns(ref);

  // The ensemble frames: one per output time.
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(d / "out" / "ensemble")) {
    if (e.path().extension() == ".csv") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  ASSERT_EQ(files.size(), 4u);  // t = 0 and the three times
  std::map<std::pair<double, int>, std::pair<double, double>> observed;  // (t, id) -> mean, var
  for (const auto& f : files) {
    const auto c = read_columns(f);
    for (std::size_t k = 0; k < c.at("id").size(); ++k) {
      EXPECT_EQ(c.at("realizations")[k], r_count);
      observed[{c.at("time")[k], static_cast<int>(c.at("id")[k])}] = {c.at("A_mean")[k],
                                                                      c.at("A_var")[k]};
    }
  }
  struct Z {
    double t;
    int i;
    double zm, zv, lambda;
  };
  std::vector<Z> zs;
  double wall_mass = 0;
  for (std::size_t k = 0; k < exact.at("t").size(); ++k) {
    const double t = exact.at("t")[k];
    const int i = static_cast<int>(exact.at("voxel")[k]);
    const auto it = observed.find({t, i});
    ASSERT_NE(it, observed.end()) << "t " << t << " particle " << i;
    const auto [mean, var] = it->second;
    if (s.particles.kind(static_cast<std::size_t>(i)) != ParticleKind::kFluid) {
      wall_mass += mean;
      continue;
    }
    const double lam = exact.at("mean")[k];
    EXPECT_NEAR(exact.at("var")[k], lam, 1e-9 * std::max(1.0, lam));  // Poisson
    if (lam < 0.05) continue;
    const double r = r_count, mu4 = lam + 3 * lam * lam;
    const double zm = (mean - lam) / std::sqrt(lam / r);
    const double zv = (var - lam) / std::sqrt((mu4 - lam * lam * (r - 3) / (r - 1)) / r);
    zs.push_back({t, i, zm, zv, lam});
  }
  EXPECT_EQ(wall_mass, 0.0);  // no molecule enters a wall
  const int m = 2 * static_cast<int>(zs.size());
  const double z_star =
      boost::math::quantile(boost::math::normal(), 1.0 - 1e-3 / (2.0 * m));  // Bonferroni
  double worst_m = 0, worst_v = 0, sum_z2 = 0;
  for (const auto& z : zs) {
    EXPECT_LE(std::fabs(z.zm), z_star) << "mean, t " << z.t << " particle " << z.i;
    EXPECT_LE(std::fabs(z.zv), z_star) << "variance, t " << z.t << " particle " << z.i;
    worst_m = std::max(worst_m, std::fabs(z.zm));
    worst_v = std::max(worst_v, std::fabs(z.zv));
    sum_z2 += z.zm * z.zm;
  }
  std::printf(
      "geometry RDME: %zu particles (%zu producing), R = %d, %zu (time, particle) pairs with "
      "lambda >= 0.05: max |z| mean %.2f, variance %.2f (z* = %.2f at 1e-3 family-wise); "
      "mean z^2 of the means %.3f\n",
      n, producing, r_count, zs.size(), worst_m, worst_v, z_star,
      sum_z2 / static_cast<double>(zs.size()));
  EXPECT_GT(zs.size(), 100u);
  // Aggregate: at one time the particles' counts are independent (Poisson), so the sum of the
  // squared mean z over them is chi-square with one degree of freedom per particle (asymptotically
  // in R); upper tail at 1e-3 per time. This sees a small bias shared by many particles.
  for (const double t : spec.times) {
    double chi2 = 0;
    int dof = 0;
    for (const auto& z : zs) {
      if (z.t != t) continue;
      chi2 += z.zm * z.zm;
      ++dof;
    }
    const double p = boost::math::cdf(
        boost::math::complement(boost::math::chi_squared(static_cast<double>(dof)), chi2));
    std::printf("  t = %.1f: sum z^2 of the means %.1f over %d particles, p = %.3g\n", t, chi2, dof,
                p);
    EXPECT_GT(p, 1e-3) << "t = " << t;
  }
  if (!HasFailure()) fs::remove_all(d);
}

}  // namespace
}  // namespace sadr::e2e
