// SPDX-License-Identifier: MIT
#include "bvh.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

namespace sadr::geometry {
namespace {

constexpr double kBvhPi = std::numbers::pi;

/// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5).
Vec3 closest_on_triangle(Vec3 p, Vec3 a, Vec3 b, Vec3 c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  }
  const double denom = va + vb + vc;
  if (!(denom > 0)) return a;  // degenerate triangle
  const double v = vb / denom, w = vc / denom;
  return a + v * ab + w * ac;
}

Vec3 closest_on_segment(Vec3 p, Vec3 a, Vec3 b) {
  const Vec3 ab = b - a;
  const double l2 = dot(ab, ab);
  const double t = l2 > 0 ? std::clamp(dot(p - a, ab) / l2, 0.0, 1.0) : 0.0;
  return a + t * ab;
}

}  // namespace

Bvh::Bvh(int dimension, std::vector<Element> elements, int leaf_size)
    : dim_(dimension), leaf_size_(std::max(1, leaf_size)), elems_(std::move(elements)) {
  const std::size_t n = elems_.size();
  order_.resize(n);
  std::iota(order_.begin(), order_.end(), 0);
  centroid_.resize(n);
  area_vec_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Element& e = elems_[i];
    if (dim_ == 3) {
      centroid_[i] = (e[0] + e[1] + e[2]) / 3.0;
      area_vec_[i] = 0.5 * cross(e[1] - e[0], e[2] - e[0]);
    } else {
      centroid_[i] = 0.5 * (e[0] + e[1]);
      const Vec3 d = e[1] - e[0];
      area_vec_[i] = {d.y, -d.x, 0};
    }
  }
  nodes_.reserve(2 * n / leaf_size_ + 2);
  if (n > 0) build(0, static_cast<int>(n));
  // Put elements in leaf order so that leaves read contiguous memory.
  std::vector<Element> e2(n);
  for (std::size_t k = 0; k < n; ++k) e2[k] = elems_[order_[k]];
  elems_ = std::move(e2);
}

int Bvh::build(int begin, int end) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.push_back({});
  Node node;
  node.begin = begin;
  node.end = end;
  Aabb cbox;
  double area = 0;
  Vec3 weighted;
  for (int k = begin; k < end; ++k) {
    const int i = order_[k];
    const Element& e = elems_[i];
    for (int v = 0; v < dim_; ++v) node.box.add(e[v]);
    cbox.add(centroid_[i]);
    const double a = norm(area_vec_[i]);
    area += a;
    weighted += a * centroid_[i];
    node.area_vec += area_vec_[i];
  }
  node.center = area > 0 ? weighted / area : node.box.center();
  for (int k = begin; k < end; ++k) {
    const Element& e = elems_[order_[k]];
    for (int v = 0; v < dim_; ++v) node.radius = std::max(node.radius, norm(e[v] - node.center));
  }
  if (end - begin > leaf_size_) {
    const Vec3 ext = cbox.extent();
    const int axis = (ext.x >= ext.y && ext.x >= ext.z) ? 0 : (ext.y >= ext.z ? 1 : 2);
    const int mid = (begin + end) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                     [&](int a, int b) { return centroid_[a][axis] < centroid_[b][axis]; });
    node.left = build(begin, mid);
    node.right = build(mid, end);
  }
  nodes_[id] = node;
  return id;
}

double Bvh::element_winding(const Element& e, Vec3 p) const {
  const Vec3 a = e[0] - p, b = e[1] - p;
  if (dim_ == 2) return std::atan2(a.x * b.y - a.y * b.x, a.x * b.x + a.y * b.y) / (2 * kBvhPi);
  const Vec3 c = e[2] - p;
  const double la = norm(a), lb = norm(b), lc = norm(c);
  const double num = dot(a, cross(b, c));
  const double den = la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb;
  return 2 * std::atan2(num, den) / (4 * kBvhPi);
}

double Bvh::winding_node(int n, Vec3 p, double beta) const {
  const Node& node = nodes_[n];
  if (beta > 0) {
    const Vec3 r = node.center - p;
    const double r2 = norm2(r);
    if (r2 > beta * beta * node.radius * node.radius) {
      // The node as one dipole N at its centre (w = N . r / (4 pi |r|^3), 2D: / (2 pi |r|^2)).
      // The second-order term of Barill et al. was tried and dropped: on curved patches it is of
      // the size of the third and made the error larger (docs/geometry.md).
      return dim_ == 3 ? dot(node.area_vec, r) / (4 * kBvhPi * r2 * std::sqrt(r2))
                       : dot(node.area_vec, r) / (2 * kBvhPi * r2);
    }
  }
  if (node.left < 0) {
    double w = 0;
    for (int k = node.begin; k < node.end; ++k) w += element_winding(elems_[k], p);
    return w;
  }
  return winding_node(node.left, p, beta) + winding_node(node.right, p, beta);
}

double Bvh::winding(Vec3 p, double beta) const {
  return nodes_.empty() ? 0.0 : winding_node(0, p, beta);
}

Vec3 Bvh::element_closest(const Element& e, Vec3 p) const {
  return dim_ == 3 ? closest_on_triangle(p, e[0], e[1], e[2]) : closest_on_segment(p, e[0], e[1]);
}

Bvh::Hit Bvh::closest(Vec3 p, double max_distance2) const {
  Hit best;
  best.distance2 = max_distance2;
  if (nodes_.empty()) return best;
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (node.box.distance2(p) >= best.distance2) continue;
    if (node.left < 0) {
      for (int k = node.begin; k < node.end; ++k) {
        const Vec3 q = element_closest(elems_[k], p);
        const double d2 = norm2(q - p);
        if (d2 < best.distance2) best = {q, d2, order_[k]};
      }
      continue;
    }
    const double dl = nodes_[node.left].box.distance2(p);
    const double dr = nodes_[node.right].box.distance2(p);
    // Push the farther child first so the nearer one is visited first.
    if (dl < dr) {
      stack[top++] = node.right;
      stack[top++] = node.left;
    } else {
      stack[top++] = node.left;
      stack[top++] = node.right;
    }
  }
  return best;
}

Vec3 Bvh::element_normal(int i) const {
  return normalized(area_vec_[i]);
}

}  // namespace sadr::geometry
