// SPDX-License-Identifier: MIT
/// \file reaction_equation.hpp
/// Parser for reaction equations written as text in scene files.
#pragma once

#include <string_view>
#include <vector>

#include "sadr/orchestrator/scene.hpp"

namespace sadr::orchestrator {

/// A parsed equation; species names are not checked against a scene here.
struct ReactionEquation {
  std::vector<StoichiometryEntry> reactants;  ///< merged: "A + A" -> {A, 2}
  std::vector<StoichiometryEntry> products;
  bool reversible = false;  ///< "<->"
};

/// Parses "A + B -> C", "2 A -> 0", "2A -> B", "R + L <-> RL", "0 -> A",
/// "A -> " (an empty side, "0" and "∅" all mean no species).
/// @throws sadr::InvalidArgument with a message saying what is wrong and
///   what is allowed (no file location: the caller adds it).
ReactionEquation parse_reaction_equation(std::string_view text);

}  // namespace sadr::orchestrator
