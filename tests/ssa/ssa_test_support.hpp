// SPDX-License-Identifier: MIT
/// \file ssa_test_support.hpp
/// Helpers for the ssa core tests: particle sets, Bonferroni z tests, CSV reading.
#pragma once

#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/common/status.hpp"
#include "sadr/ssa/model.hpp"

namespace sadr::ssa::testing {

/// Bonferroni critical value z* = Phi^-1(1 - alpha_fw / (2 M)) (refs/README.md section 8):
/// max |z_i| <= z* over M comparison points has family-wise false-failure rate <= alpha_fw.
inline double z_star(double alpha_fw, int m) {
  return boost::math::quantile(boost::math::normal(), 1.0 - alpha_fw / (2.0 * m));
}

/// Upper-tail p value of a chi-square statistic.
inline double chi2_p(double stat, int dof) {
  return boost::math::cdf(boost::math::complement(boost::math::chi_squared(dof), stat));
}

/// 4th central moment of Binomial(n, p).
inline double binomial_mu4(double n, double p) {
  const double v = n * p * (1 - p);
  return v * (1 + 3 * (n - 2) * p * (1 - p));
}

/// z statistic of a sample variance s2 against the exact variance var with
/// exact 4th central moment mu4 (refs/README.md section 8).
inline double variance_z(double s2, double var, double mu4, double r) {
  return (s2 - var) / std::sqrt((mu4 - var * var * (r - 3) / (r - 1)) / r);
}

/// Running mean / variance of an ensemble at one comparison point.
struct Moments {
  double n = 0, sum = 0, sum2 = 0;
  void add(double x) { n += 1, sum += x, sum2 += x * x; }
  [[nodiscard]] double mean() const { return sum / n; }
  [[nodiscard]] double var() const { return (sum2 - sum * sum / n) / (n - 1); }
};

/// A box of `cells` spacings dx per active axis, from 0.
inline Box make_box(int dim, double length, bool periodic) {
  Box b;
  b.dimension = dim;
  for (int a = 0; a < 3; ++a) {
    b.lo[a] = 0;
    b.hi[a] = a < dim ? length : 1.0;
    b.periodic[a] = a < dim && periodic;
  }
  return b;
}

/// Regular lattice of n^dim particles at (k + 0.5) dx, m = rho = 1 scaled so V = dx^dim;
/// jitter > 0 moves each coordinate uniformly by +-jitter*dx and scales m by
/// a factor in [1 - mass_spread, 1 + mass_spread].
inline ParticleState make_lattice(int dim, int n, double dx, double jitter = 0,
                                  double mass_spread = 0, std::uint64_t seed = 1) {
  ParticleState p;
  p.dimension = dim;
  std::size_t count = 1;
  for (int a = 0; a < dim; ++a) count *= static_cast<std::size_t>(n);
  p.resize(count, false);
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (std::size_t i = 0; i < count; ++i) {
    std::size_t rest = i;
    for (int a = 0; a < dim; ++a) {
      const double k = static_cast<double>(rest % n);
      rest /= n;
      double x = (k + 0.5) * dx + jitter * dx * u(gen);
      p.positions[3 * i + a] = x;
    }
    p.densities[i] = 1.0;
    p.masses[i] = std::pow(dx, dim) * (1.0 + mass_spread * u(gen));
  }
  return p;
}

/// One species model on the given box with diffusivity kappa.
inline Model diffusion_model(const Box& box, double h, double kappa,
                             JumpConvention conv = JumpConvention::kVolume) {
  Model m;
  m.species = {{"A", kappa}};
  m.box = box;
  m.smoothing_length = h;
  m.convention = conv;
  return m;
}

/// Rows of a refs CSV (comment lines '#', one header row, quoted fields allowed).
inline std::vector<std::map<std::string, std::string>> read_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  auto split = [](const std::string& line) {
    std::vector<std::string> out;
    std::string cur;
    bool quoted = false;
    for (char c : line) {
      if (c == '"') {
        quoted = !quoted;
      } else if (c == ',' && !quoted) {
        out.push_back(cur);
        cur.clear();
      } else {
        cur += c;
      }
    }
    out.push_back(cur);
    return out;
  };
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    auto f = split(line);
    if (header.empty()) {
      header = f;
      continue;
    }
    std::map<std::string, std::string> row;
    for (std::size_t k = 0; k < header.size() && k < f.size(); ++k) row[header[k]] = f[k];
    rows.push_back(row);
  }
  return rows;
}

/// The message of the InvalidArgument that `f` throws, or a marker that fails
/// every find() the tests make when it throws none.
inline std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "<no InvalidArgument thrown>";
}

/// Path of a file in tests/data/refs (SADR_REFS from ctest, else the source tree).
inline std::string refs_path(const std::string& name) {
  const char* env = std::getenv("SADR_REFS");
  return std::string(env ? env : SADR_SOURCE_DIR "/tests/data/refs") + "/" + name;
}

/// kappa_eff / kappa from refs sph_consistency.csv.
inline double kappa_ratio(int dim, double eps, double h_over_dx) {
  for (const auto& row : read_csv(refs_path("sph_consistency.csv"))) {
    if (std::stoi(row.at("dim")) == dim && std::abs(std::stod(row.at("eps")) - eps) < 1e-12 &&
        row.at("h_over_dx") != "inf" &&
        std::abs(std::stod(row.at("h_over_dx")) - h_over_dx) < 1e-9) {
      return std::stod(row.at("kappa_eff_over_kappa"));
    }
  }
  throw std::runtime_error("no sph_consistency row for the requested case");
}

}  // namespace sadr::ssa::testing
