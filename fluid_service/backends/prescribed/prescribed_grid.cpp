// SPDX-License-Identifier: MIT
// GridField (see prescribed_grid.hpp): reading and checking the CSV grid, multilinear look-up.
#include "prescribed_grid.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "sadr/common/input_file.hpp"
#include "sadr/common/status.hpp"

namespace sadr::fluid {
namespace {

constexpr const char* kCoord[3] = {"x", "y", "z"};
constexpr const char* kVel[3] = {"ux", "uy", "uz"};

std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream s(line);
  while (std::getline(s, cell, ',')) {
    const auto b = cell.find_first_not_of(" \t\r");
    const auto e = cell.find_last_not_of(" \t\r");
    out.push_back(b == std::string::npos ? std::string() : cell.substr(b, e - b + 1));
  }
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

bool blank_or_comment(const std::string& line) {
  const auto b = line.find_first_not_of(" \t\r");
  return b == std::string::npos || line[b] == '#';
}

std::string columns_allowed(int d) {
  std::string s;
  for (int a = 0; a < d; ++a) s += std::string(s.empty() ? "" : ", ") + kCoord[a];
  for (int a = 0; a < d; ++a) s += std::string(", ") + kVel[a];
  return s;
}

std::string point_text(const std::array<double, 3>& x, int d) {
  std::string s = "(";
  for (int a = 0; a < d; ++a) s += (a ? ", " : "") + format_short(x[a]);
  return s + ")";
}

/// The distinct values of `v` (sorted), those closer than `tol` to the previous one merged.
std::vector<double> distinct(std::vector<double> v, double tol) {
  std::sort(v.begin(), v.end());
  std::vector<double> out;
  for (const double x : v) {
    if (out.empty() || x - out.back() > tol) out.push_back(x);
  }
  return out;
}

}  // namespace

GridField GridField::read(const std::string& path, const Box& box) {
  GridField g;
  g.dim_ = box.dimension;
  g.path_ = path;
  const int d = box.dimension;
  try {
    require_regular_file(path, kMaxDataFileBytes, "prescribed.field_file");
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(e.what(), {{"field", "field_file"}, {"value", path}});
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InvalidArgument("prescribed.field_file: cannot open '" + path + "'",
                          {{"field", "field_file"}, {"value", path}});
  }
  auto fail = [&](int line, const std::string& msg) {
    throw InvalidArgument(path + ":" + std::to_string(line) + ": " + msg +
                              " (prescribed field_file, docs/scene-format.md)",
                          {{"file", path}, {"line", std::to_string(line)}});
  };
  std::string line;
  int line_no = 0;
  bool have_header = false;
  while (!have_header && std::getline(in, line)) {
    ++line_no;
    have_header = !blank_or_comment(line);
  }
  if (!have_header)
    fail(line_no, "no header row; the first row must name the columns " + columns_allowed(d));
  const auto header = cells(line);
  std::array<int, 3> xcol{-1, -1, -1}, ucol{-1, -1, -1};
  for (std::size_t c = 0; c < header.size(); ++c) {
    int* slot = nullptr;
    for (int a = 0; a < d; ++a) {
      if (header[c] == kCoord[a]) slot = &xcol[a];
      if (header[c] == kVel[a]) slot = &ucol[a];
    }
    if (!slot) {
      fail(line_no, "column " + std::to_string(c + 1) + " '" + header[c] +
                        "' is not a column of a " + std::to_string(d) +
                        "D field; allowed: " + columns_allowed(d));
    }
    if (*slot >= 0) {
      fail(line_no, "column '" + header[c] + "' appears twice (columns " +
                        std::to_string(*slot + 1) + " and " + std::to_string(c + 1) + ")");
    }
    *slot = static_cast<int>(c);
  }
  for (int a = 0; a < d; ++a) {
    for (const auto& [col, name] : {std::pair{xcol[a], kCoord[a]}, std::pair{ucol[a], kVel[a]}}) {
      if (col < 0) {
        fail(line_no, std::string("missing column '") + name + "'; the header must name " +
                          columns_allowed(d));
      }
    }
  }
  struct Row {
    std::array<double, 3> x{}, u{};
    int line = 0;
  };
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    ++line_no;
    if (blank_or_comment(line)) continue;
    const auto c = cells(line);
    if (c.size() != header.size()) {
      fail(line_no, std::to_string(c.size()) + " values; the header has " +
                        std::to_string(header.size()) + " columns");
    }
    Row r;
    r.line = line_no;
    auto number = [&](int col) {
      const std::string& t = c[static_cast<std::size_t>(col)];
      double v = 0.0;
      const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
      if (ec != std::errc() || ptr != t.data() + t.size() || !std::isfinite(v)) {
        fail(line_no, "column '" + header[static_cast<std::size_t>(col)] + "' = '" + t +
                          "' is not a finite number");
      }
      return v;
    };
    for (int a = 0; a < d; ++a) {
      r.x[a] = number(xcol[a]);
      r.u[a] = number(ucol[a]);
    }
    rows.push_back(r);
  }
  if (rows.empty()) fail(line_no, "no grid points after the header");

  // The grid values of each axis, and each row's node.
  std::array<double, 3> tol{};
  std::size_t nodes = 1;
  for (int a = d - 1; a >= 0; --a) {
    std::vector<double> v;
    for (const auto& r : rows) v.push_back(r.x[a]);
    const auto [mn, mx] = std::minmax_element(v.begin(), v.end());
    tol[a] = 1e-9 * (*mx - *mn);
    g.axes_[a] = distinct(std::move(v), tol[a]);
    if (g.axes_[a].size() < 2) {
      fail(rows.front().line, std::string("every point has ") + kCoord[a] + " = " +
                                  format_short(g.axes_[a].front()) + "; a " + std::to_string(d) +
                                  "D grid needs >= 2 values of " + kCoord[a]);
    }
    g.stride_[a] = nodes;
    nodes *= g.axes_[a].size();
  }
  std::vector<int> seen(nodes, 0);  // the line of each node's row
  g.u_.assign(nodes * static_cast<std::size_t>(d), 0.0);
  for (const auto& r : rows) {
    std::size_t node = 0;
    for (int a = 0; a < d; ++a) {
      const auto& ax = g.axes_[a];
      const auto it = std::lower_bound(ax.begin(), ax.end(), r.x[a] - tol[a]);
      node += static_cast<std::size_t>(it - ax.begin()) * g.stride_[a];
    }
    if (seen[node]) {
      fail(r.line, "the point " + point_text(r.x, d) + " is given twice (also on line " +
                       std::to_string(seen[node]) + ")");
    }
    seen[node] = r.line;
    for (int a = 0; a < d; ++a) g.u_[node * static_cast<std::size_t>(d) + a] = r.u[a];
  }
  if (rows.size() != nodes) {
    const auto miss =
        static_cast<std::size_t>(std::find(seen.begin(), seen.end(), 0) - seen.begin());
    std::array<double, 3> x{};
    std::string counts;
    for (int a = 0; a < d; ++a) {
      x[a] = g.axes_[a][(miss / g.stride_[a]) % g.axes_[a].size()];
      counts += std::string(a ? " x " : "") + std::to_string(g.axes_[a].size()) + " values of " +
                kCoord[a];
    }
    fail(line_no, "not a grid: the point " + point_text(x, d) + " is missing (" + counts +
                      " make " + std::to_string(nodes) + " points, " + std::to_string(rows.size()) +
                      " given; a grid has a row for every "
                      "combination of the distinct coordinates)");
  }
  for (int a = 0; a < d; ++a) {
    g.periodic_[a] = box.periodic[a];
    g.box_lo_[a] = box.lo[a];
    g.box_len_[a] = box.hi[a] - box.lo[a];
    const double t = 1e-9 * g.box_len_[a];
    if (g.periodic_[a] && (g.lo(a) > box.lo[a] + t || g.hi(a) < box.hi[a] - t)) {
      fail(line_no, std::string("along the periodic axis ") + kCoord[a] + " the grid spans [" +
                        format_short(g.lo(a)) + ", " + format_short(g.hi(a)) +
                        "]; allowed: a grid that spans the box [" + format_short(box.lo[a]) + ", " +
                        format_short(box.hi[a]) + "]");
    }
  }
  return g;
}

std::string GridField::point(const double* x) const {
  std::array<double, 3> p{x[0], x[1], x[2]};
  return point_text(p, dim_);
}

std::string GridField::extent() const {
  std::string s;
  for (int a = 0; a < dim_; ++a)
    s += (a ? " x [" : "[") + format_short(lo(a)) + ", " + format_short(hi(a)) + "]";
  return s;
}

bool GridField::velocity(const double* x, double* v) const {
  std::array<std::size_t, 3> cell{};
  std::array<double, 3> t{};
  for (int a = 0; a < dim_; ++a) {
    double s = x[a];
    if (periodic_[a]) s -= box_len_[a] * std::floor((s - box_lo_[a]) / box_len_[a]);
    const auto& ax = axes_[a];
    if (!(s >= ax.front() && s <= ax.back())) {
      if (!periodic_[a]) return false;
      s = std::clamp(s, ax.front(), ax.back());  // (round-off of the wrap)
    }
    const auto it = std::upper_bound(ax.begin(), ax.end(), s);
    const std::size_t i = std::min(static_cast<std::size_t>(it - ax.begin()), ax.size() - 1) - 1;
    cell[a] = i;
    t[a] = (s - ax[i]) / (ax[i + 1] - ax[i]);
  }
  v[0] = v[1] = v[2] = 0.0;
  const auto d = static_cast<std::size_t>(dim_);
  for (unsigned corner = 0; corner < (1u << dim_); ++corner) {
    double w = 1.0;
    std::size_t node = 0;
    for (int a = 0; a < dim_; ++a) {
      const bool up = (corner >> a) & 1u;
      w *= up ? t[a] : 1.0 - t[a];
      node += (cell[a] + (up ? 1 : 0)) * stride_[a];
    }
    for (std::size_t c = 0; c < d; ++c) v[c] += w * u_[node * d + c];
  }
  return true;
}

}  // namespace sadr::fluid
