// SPDX-License-Identifier: MIT
/// \file tdpd_parameters.cpp
/// TdpdParameters: FluidModel::backend_parameters keys and range checks.
#include <cmath>
#include <string>
#include <vector>

#include "sadr/common/status.hpp"
#include "tdpd_backend.hpp"

namespace sadr::fluid {

void TdpdParameters::apply(const std::map<std::string, double>& kv) {
  for (const auto& [key, value] : kv) {
    if (key == "a") {
      a = value;
    } else if (key == "gamma") {
      gamma = value;
    } else if (key == "s1") {
      s1 = value;
    } else if (key == "r_cc") {
      r_cc = value;
    } else if (key == "lambda") {
      lambda = value;
    } else if (key == "skin") {
      skin = value;
    } else if (key == "effective_walls") {
      if (value != 0.0 && value != 1.0) {
        throw InvalidArgument("tdpd.effective_walls = " + format_value(value) +
                              " (allowed 0 or 1)");
      }
      effective_walls = value == 1.0;
    } else if (key == "buffer_axis") {
      if (!(value >= -1.0 && value <= 2.0) || value != std::floor(value)) {
        throw InvalidArgument("tdpd.buffer_axis = " + format_value(value) +
                              " (allowed -1, 0, 1, 2)");
      }
      buffer_axis = static_cast<int>(value);
    } else if (key == "inflow_length") {
      inflow_length = value;
    } else if (key == "inflow_value") {
      inflow_value = value;
    } else {
      throw InvalidArgument("tdpd: unknown parameter '" + key +
                            "' (known: a, gamma, s1, r_cc, lambda, skin, effective_walls, "
                            "buffer_axis, inflow_length, inflow_value)");
    }
  }
}

void TdpdParameters::validate(double r_c) const {
  std::vector<std::string> bad;
  auto need = [&](bool ok, const char* field, double v, const char* range) {
    if (!ok)
      bad.push_back(std::string("tdpd.") + field + " = " + format_value(v) + " (allowed " + range +
                    ")");
  };
  need(std::isfinite(a) && a >= 0.0, "a", a, ">= 0");
  need(std::isfinite(gamma) && gamma >= 0.0, "gamma", gamma, ">= 0");
  need(std::isfinite(s1) && s1 >= 0.0, "s1", s1, ">= 0");
  need(std::isfinite(r_cc) && r_cc >= 0.0 && r_cc <= r_c, "r_cc", r_cc, "[0, r_c] (0 = r_c)");
  need(std::isfinite(lambda) && lambda >= 0.0 && lambda <= 1.0, "lambda", lambda, "[0, 1]");
  need(std::isfinite(skin) && skin >= 0.0 && skin <= 1.0, "skin", skin, "[0, 1] (0 = model)");
  need(std::isfinite(inflow_length) && inflow_length >= 0.0, "inflow_length", inflow_length,
       ">= 0");
  need(std::isfinite(inflow_value), "inflow_value", inflow_value, "finite");
  if (!bad.empty()) {
    std::string msg = "invalid tDPD parameters:";
    for (const auto& b : bad) msg += "\n  " + b;
    throw InvalidArgument(msg);
  }
}

}  // namespace sadr::fluid
