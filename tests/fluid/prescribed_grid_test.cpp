// SPDX-License-Identifier: MIT
// The "prescribed" backend's `csv` field (backends/prescribed/prescribed_grid.hpp): a steady
// field read from a CSV grid, interpolated multilinearly. Trajectories against the analytic
// fields the CSVs sample (exact for a linear field, second order in the grid spacing otherwise),
// and the refusals of files that are not a grid.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "sadr/common/status.hpp"
#include "sadr/fluid/builtin_backends.hpp"

namespace sadr::fluid {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kCsv = 4;  // the index of `csv` among the schema's `field` choices

std::unique_ptr<FluidBackend> make() {
  BackendRegistry r;
  register_builtin_backends(r);
  return r.create("prescribed");
}

std::string write_file(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "sadr_grid_" + name + ".csv";
  std::ofstream(path) << text;
  return path;
}

using Field2 = std::function<std::array<double, 2>(double, double)>;

/// The CSV of `u` sampled on the grid xs x ys (rows in y-major order, 17 digits).
std::string sample(const Field2& u, const std::vector<double>& xs, const std::vector<double>& ys) {
  std::string s = "x,y,ux,uy\n";
  char b[128];
  for (const double y : ys) {
    for (const double x : xs) {
      const auto v = u(x, y);
      std::snprintf(b, sizeof b, "%.17g,%.17g,%.17g,%.17g\n", x, y, v[0], v[1]);
      s += b;
    }
  }
  return s;
}

std::vector<double> nodes(double lo, double hi, int cells) {
  std::vector<double> v;
  for (int k = 0; k <= cells; ++k) v.push_back(lo + (hi - lo) * k / cells);
  return v;
}

/// Particles at `xy` in a 2D box [lo, hi]^2 (periodic or not), all fluid.
struct Scene2 {
  FluidModel model;
  ParticleState state;
  Scene2(double lo, double hi, bool periodic, const std::vector<std::array<double, 2>>& xy) {
    model.box.dimension = 2;
    model.box.lo = {lo, lo, 0};
    model.box.hi = {hi, hi, 1};
    model.box.periodic = {periodic, periodic, false};
    model.smoothing_length = 0.5;
    state.dimension = 2;
    state.resize(xy.size(), true);
    for (std::size_t i = 0; i < xy.size(); ++i) {
      state.positions[3 * i] = xy[i][0];
      state.positions[3 * i + 1] = xy[i][1];
      state.positions[3 * i + 2] = 0;
      state.masses[i] = 1;
      state.densities[i] = 1;
    }
  }
  /// Positions after `steps` coupling steps of `dt`, with the CSV `path` (or `params` as given).
  std::vector<double> run(std::map<std::string, double> params, const std::string& path, double dt,
                          int steps) {
    model.backend_parameters = std::move(params);
    model.backend_files.clear();
    if (!path.empty()) model.backend_files["field_file"] = path;
    auto b = make();
    b->initialize(model, state, {});
    for (int k = 0; k < steps; ++k) b->advance(static_cast<std::uint64_t>(k), dt);
    ParticleState out;
    b->read_state(out);
    return out.positions;
  }
};

/// The root mean square distance between two position lists (minimum image in a box of side L).
double rms(const std::vector<double>& a, const std::vector<double>& b, double box = 0) {
  double s = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    double d = a[i] - b[i];
    if (box > 0) d -= box * std::round(d / box);
    s += d * d;
  }
  return std::sqrt(s / static_cast<double>(a.size() / 3));
}

// A linear field (solid-body rotation) is interpolated exactly, on any rectilinear grid: the
// trajectories are those of the analytic `rotation` field, to round-off.
TEST(PrescribedGrid, ALinearFieldIsInterpolatedExactly) {
  const double omega = 2 * kPi;
  const Field2 rot = [&](double x, double y) { return std::array{-omega * y, omega * x}; };
  const std::vector<double> xs{-4, -1.5, 0, 0.25, 2, 4}, ys{-4, -3, 1, 4};  // uneven spacing
  const std::string path = write_file("rotation", sample(rot, xs, ys));
  Scene2 s(-4, 4, false, {{1.0, 0.0}, {-0.7, 0.3}, {0.2, -1.9}});
  s.model.max_time_step = 0.01;
  const auto got = s.run({{"field", kCsv}, {"integrator", 1}}, path, 0.1, 10);
  const auto want = s.run({{"field", 3}, {"omega", omega}, {"integrator", 1}}, "", 0.1, 10);
  const double e = rms(got, want);
  std::printf("RESULT prescribed csv rotation rms_vs_analytic=%.3e\n", e);
  EXPECT_LT(e, 1e-12);
}

/// Poiseuille u_x = 4 U y (1 - y) sampled with `cells` cells across; 200 particles spread over
/// the channel advected for T = 1 (RK4 is exact: u_x depends on y only), against the analytic
/// field's exact map. Returns the RMS position error.
double poiseuille_error(int cells) {
  const Field2 u = [](double, double y) { return std::array{4.0 * y * (1.0 - y), 0.0}; };
  const std::string path =
      write_file("poiseuille" + std::to_string(cells), sample(u, {0.0, 1.0}, nodes(0, 1, cells)));
  std::vector<std::array<double, 2>> xy;
  for (int k = 0; k < 200; ++k) xy.push_back({0.5, (k + 0.5) / 200.0});
  Scene2 s(0, 1, false, xy);
  s.model.box.periodic = {true, false, false};
  s.model.max_time_step = 0.25;
  const auto got = s.run({{"field", kCsv}, {"integrator", 1}}, path, 0.5, 2);
  const auto want = s.run({{"field", 2}, {"max_velocity", 1.0}}, "", 0.5, 2);
  return rms(got, want, 1.0);
}

/// The cellular flow u = (sin(pi x) cos(pi y), -cos(pi x) sin(pi y)) on the periodic box
/// [0, 2]^2 sampled with `cells` cells per axis; 64 particles advected for T = 0.5 with RK4
/// sub-steps of 1e-3, against RK4 of the analytic field with the same sub-steps (its own time
/// error ~1e-13). Returns the RMS position error.
double cellular_error(int cells) {
  auto u = [](double x, double y) {
    return std::array{std::sin(kPi * x) * std::cos(kPi * y),
                      -std::cos(kPi * x) * std::sin(kPi * y)};
  };
  const std::string path = write_file("cellular" + std::to_string(cells),
                                      sample(u, nodes(0, 2, cells), nodes(0, 2, cells)));
  std::vector<std::array<double, 2>> xy;
  for (int i = 0; i < 8; ++i) {
    for (int j = 0; j < 8; ++j) xy.push_back({0.1 + 0.23 * i + 0.01 * j, 0.07 + 0.241 * j});
  }
  Scene2 s(0, 2, true, xy);
  const double dt = 1e-3;
  s.model.max_time_step = dt;
  const auto got = s.run({{"field", kCsv}, {"integrator", 1}}, path, 0.25, 2);
  std::vector<double> want;
  for (auto p : xy) {
    for (int k = 0; k < 500; ++k) {  // classical RK4 of the analytic field
      const auto k1 = u(p[0], p[1]);
      const auto k2 = u(p[0] + 0.5 * dt * k1[0], p[1] + 0.5 * dt * k1[1]);
      const auto k3 = u(p[0] + 0.5 * dt * k2[0], p[1] + 0.5 * dt * k2[1]);
      const auto k4 = u(p[0] + dt * k3[0], p[1] + dt * k3[1]);
      for (int a = 0; a < 2; ++a) p[a] += dt / 6 * (k1[a] + 2 * k2[a] + 2 * k3[a] + k4[a]);
    }
    want.insert(want.end(), {p[0], p[1], 0.0});
  }
  return rms(got, want, 2.0);
}

// Bilinear interpolation is second order in the spacing: halving it divides the trajectory
// error by 4 (observed order within [1.8, 2.2] on three spacings), for a field that varies in
// one direction (Poiseuille, against its exact map) and one that varies in both (cellular flow).
TEST(PrescribedGrid, TrajectoriesConvergeWithOrderTwoInTheSpacing) {
  for (const char* name : {"poiseuille", "cellular"}) {
    double prev = 0;
    for (const int cells : {4, 8, 16}) {
      const double e = std::string(name) == "poiseuille" ? poiseuille_error(cells * 2)
                                                         : cellular_error(cells * 2);
      std::printf("RESULT prescribed csv %s cells=%d rms_error=%.3e", name, cells * 2, e);
      if (prev > 0) {
        const double order = std::log2(prev / e);
        std::printf(" observed_order=%.3f", order);
        EXPECT_GT(order, 1.8) << name << " " << cells;
        EXPECT_LT(order, 2.2) << name << " " << cells;
      }
      std::printf("\n");
      prev = e;
    }
  }
}

/// The message of initialising a 2D scene (box [0, 1]^2, x periodic) on the CSV `text`.
std::string refusal(const std::string& name, const std::string& text,
                    std::map<std::string, double> params = {{"field", kCsv}, {"integrator", 1}}) {
  Scene2 s(0, 1, false, {{0.5, 0.5}});
  s.model.box.periodic = {true, false, false};
  s.model.backend_parameters = std::move(params);
  s.model.backend_files["field_file"] = write_file(name, text);
  try {
    make()->initialize(s.model, s.state, {});
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "(accepted)";
}

// What is not a grid is refused with file:line, the column and the value.
TEST(PrescribedGrid, RefusesFilesThatAreNotAGrid) {
  const std::string good = "x,y,ux,uy\n0,0,1,0\n1,0,1,0\n0,1,1,0\n1,1,1,0\n";
  EXPECT_EQ(refusal("good", good), "(accepted)");
  EXPECT_EQ(refusal("comments", "# made by hand\n" + good + "\n# end\n"), "(accepted)");
  struct Case {
    const char* name;
    std::string text;
    std::string want;
  };
  const Case cases[] = {
      {"empty", "", ":0: no header row; the first row must name the columns x, y, ux, uy"},
      {"unknown_column", "x,y,ux,uz\n", ":1: column 4 'uz' is not a column of a 2D field"},
      {"twice", "x,y,ux,uy,x\n", ":1: column 'x' appears twice (columns 1 and 5)"},
      {"missing_column", "x,y,ux\n", ":1: missing column 'uy'"},
      {"row_length", "x,y,ux,uy\n0,0,1,0\n1,0,1\n", ":3: 3 values; the header has 4 columns"},
      {"not_a_number", "x,y,ux,uy\n0,0,1,0\n1,0,fast,0\n",
       ":3: column 'ux' = 'fast' is not a "
       "finite number"},
      {"nan", "x,y,ux,uy\n0,0,nan,0\n", ":2: column 'ux' = 'nan' is not a finite number"},
      {"no_rows", "x,y,ux,uy\n", ":1: no grid points after the header"},
      {"given_twice", good + "1,0,2,0\n", ":6: the point (1, 0) is given twice (also on line 3)"},
      {"missing_point", "x,y,ux,uy\n0,0,1,0\n1,0,1,0\n0,1,1,0\n",
       ":4: not a grid: the point (1, 1) is missing (2 values of x x 2 values of y make 4 points, "
       "3 "
       "given"},
      {"one_value", "x,y,ux,uy\n0,0.5,1,0\n1,0.5,1,0\n",
       ":2: every point has y = 0.5; a 2D grid needs >= 2 values of y"},
      {"periodic_span", "x,y,ux,uy\n0,0,1,0\n0.5,0,1,0\n0,1,1,0\n0.5,1,1,0\n",
       ":5: along the periodic axis x the grid spans [0, 0.5]; allowed: a grid that spans the box "
       "[0, 1]"},
  };
  for (const auto& c : cases) {
    const std::string got = refusal(c.name, c.text);
    EXPECT_NE(got.find("sadr_grid_" + std::string(c.name) + ".csv" + c.want), std::string::npos)
        << c.name << ": " << got;
  }
  EXPECT_NE(refusal("exact", good, {{"field", kCsv}}).find("field csv needs integrator rk4"),
            std::string::npos);
}

// Without a file, with a file for another field, or with a file that does not open: refused.
TEST(PrescribedGrid, RefusesAMissingOrUnusedFile) {
  Scene2 s(0, 1, false, {{0.5, 0.5}});
  s.model.backend_parameters = {{"field", kCsv}, {"integrator", 1}};
  EXPECT_THROW(
      {
        try {
          make()->initialize(s.model, s.state, {});
        } catch (const InvalidArgument& e) {
          EXPECT_NE(std::string(e.what()).find("field csv needs field_file"), std::string::npos)
              << e.what();
          throw;
        }
      },
      InvalidArgument);
  s.model.backend_files["field_file"] = ::testing::TempDir() + "sadr_grid_absent.csv";
  try {
    make()->initialize(s.model, s.state, {});
    ADD_FAILURE() << "an absent file was accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("cannot open"), std::string::npos) << e.what();
  }
  s.model.backend_parameters = {{"field", 0}, {"ux", 1}};
  try {
    make()->initialize(s.model, s.state, {});
    ADD_FAILURE() << "field_file with field uniform was accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("field_file applies to field csv only"), std::string::npos)
        << e.what();
  }
}

// A particle that leaves the grid along a walled axis stops the run, naming it.
TEST(PrescribedGrid, AParticleLeavingTheGridIsRefused) {
  const Field2 u = [](double, double) { return std::array{0.0, 1.0}; };
  const std::string path = write_file("leave", sample(u, {0.0, 1.0}, {0.0, 0.6}));
  Scene2 s(0, 1, false, {{0.5, 0.1}, {0.5, 0.7}});
  s.model.backend_parameters = {{"field", kCsv}, {"integrator", 1}};
  s.model.backend_files["field_file"] = path;
  try {
    make()->initialize(s.model, s.state, {});
    ADD_FAILURE() << "a particle outside the grid was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("particle 1 at (0.5, 0.7) lies outside the field's grid"),
              std::string::npos)
        << e.what();
  }
  s.state.positions[4] = 0.3;  // both inside; particle 1 reaches y = 0.6 at t = 0.3
  auto b = make();
  b->initialize(s.model, s.state, {});
  b->advance(0, 0.2);
  try {
    b->advance(1, 0.2);
    ADD_FAILURE() << "a particle left the grid silently";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), StatusCode::kOutOfRange);
    EXPECT_NE(std::string(e.what()).find("particle 1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sadr::fluid
