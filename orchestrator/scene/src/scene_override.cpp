// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/scene_override.hpp"

#include <string_view>
#include <vector>

#include "sadr/common/status.hpp"
#include "scene_override_tree.hpp"

namespace sadr::orchestrator {
namespace {

/// One step of a path: a map key, or a list selector ([name] or [index]).
struct Step {
  std::string text;
  bool selector = false;
};

bool is_index(std::string_view s) {
  return !s.empty() && s.size() <= 9 && s.find_first_not_of("0123456789") == std::string_view::npos;
}

/// The steps of `path`; throws naming `what` on a syntax error.
std::vector<Step> split_path(std::string_view path, std::string_view what) {
  auto fail = [&](const std::string& why) {
    throw InvalidArgument("--set " + std::string(what) + ": " + why +
                          " (expected PATH=VALUE, PATH like fluid.sound_speed, "
                          "reactions[annihilation].rate or species[0].diffusivity)");
  };
  std::vector<Step> steps;
  std::size_t i = 0;
  bool need_key = true;
  while (i < path.size()) {
    if (path[i] == '[') {
      const std::size_t close = path.find(']', i);
      if (close == std::string_view::npos) fail("'[' without ']'");
      if (steps.empty()) fail("a path starts with a key, not '['");
      const std::string_view sel = path.substr(i + 1, close - i - 1);
      if (sel.empty()) fail("empty '[]'");
      steps.push_back({std::string(sel), true});
      i = close + 1;
      need_key = false;
      continue;
    }
    if (path[i] == '.') {
      if (need_key) fail("empty key in '" + std::string(path) + "'");
      ++i;
      need_key = true;
      continue;
    }
    if (!need_key) fail("expected '.' or '[' after ']' in '" + std::string(path) + "'");
    const std::size_t end = path.find_first_of(".[]", i);
    const std::string_view key = path.substr(i, end == std::string_view::npos ? end : end - i);
    if (key.empty()) fail("unexpected ']' in '" + std::string(path) + "'");
    steps.push_back({std::string(key), false});
    i = end == std::string_view::npos ? path.size() : end;
    need_key = false;
  }
  if (steps.empty() || need_key) fail("empty path or trailing '.'");
  return steps;
}

std::string quote(std::string_view s) {
  std::string q(1, '\'');
  q.append(s).push_back('\'');
  return q;
}

std::string kind_of(const YAML::Node& n) {
  if (n.IsSequence()) return "a list";
  if (n.IsMap()) return "a map";
  if (n.IsScalar()) return "the value '" + n.Scalar() + "'";
  return "nothing";
}

}  // namespace

SceneOverride parse_override(std::string_view text) {
  const std::size_t eq = text.find('=');
  if (eq == std::string_view::npos) {
    throw InvalidArgument("--set '" + std::string(text) +
                          "': expected PATH=VALUE, e.g. --set fluid.sound_speed=20");
  }
  SceneOverride o{std::string(text.substr(0, eq)), std::string(text.substr(eq + 1))};
  split_path(o.path, quote(text));  // syntax check
  return o;
}

std::vector<SceneOverride> parse_overrides(const std::vector<std::string>& texts) {
  std::vector<SceneOverride> out;
  out.reserve(texts.size());
  for (const auto& t : texts) out.push_back(parse_override(t));
  return out;
}

namespace detail {

void apply_overrides(YAML::Node& root, std::span<const SceneOverride> overrides,
                     Diagnostics& diag) {
  for (const SceneOverride& o : overrides) {
    const std::string text = o.text();
    auto fail = [&](const std::string& why) { diag.error({}, "", "--set " + text + ": " + why); };
    YAML::Node value;
    try {
      value = YAML::Load(o.value);
    } catch (const YAML::Exception& e) {
      fail("the value is not valid YAML: " + e.msg);
      continue;
    }
    const std::vector<Step> steps = split_path(o.path, quote(text));
    YAML::Node node = root;  // handles; reset() rebinds, operator= would assign
    std::string resolved;
    bool ok = true;
    for (std::size_t k = 0; k < steps.size() && ok; ++k) {
      const Step& s = steps[k];
      const bool last = k + 1 == steps.size();
      const std::string where = resolved.empty() ? "the scene" : "'" + resolved + "'";
      if (!s.selector) {
        if (!node.IsMap() && node.IsDefined() && !node.IsNull()) {
          fail(where + " is " + kind_of(node) + ", not a map with key '" + s.text + "'");
          ok = false;
          break;
        }
        resolved += (resolved.empty() ? "" : ".") + s.text;
        if (last) {
          node[s.text] = value;
        } else {
          YAML::Node next = node[s.text];
          if (!next.IsDefined() || next.IsNull()) next = YAML::Node(YAML::NodeType::Map);
          node.reset(node[s.text]);
        }
        continue;
      }
      if (!node.IsSequence()) {
        fail(where + " is " + kind_of(node) + ", not a list (selector [" + s.text + "])");
        ok = false;
        break;
      }
      std::size_t index = node.size();
      if (is_index(s.text)) {
        index = std::stoul(s.text);
        if (index >= node.size()) {
          fail("index " + s.text + " is out of range: " + where + " has " +
               std::to_string(node.size()) + " items" +
               (node.size() > 0 ? " (0.." + std::to_string(node.size() - 1) + ")" : ""));
          ok = false;
          break;
        }
      } else {
        std::vector<std::string> names;
        for (std::size_t j = 0; j < node.size(); ++j) {
          const YAML::Node item = node[j];
          const YAML::Node name = item.IsMap() ? item["name"] : YAML::Node();
          if (!name.IsDefined() || !name.IsScalar()) continue;
          if (name.Scalar() == s.text && index == node.size()) index = j;
          names.push_back(name.Scalar());
        }
        if (index == node.size()) {
          std::vector<std::string_view> views(names.begin(), names.end());
          std::string msg = "no item named '" + s.text + "' in " + where;
          if (auto near = nearest_name(s.text, views)) msg += "; did you mean '" + *near + "'?";
          msg +=
              names.empty() ? " (its items have no names)" : " (names: " + join_names(views) + ")";
          fail(msg);
          ok = false;
          break;
        }
      }
      resolved.append("[").append(std::to_string(index)).append("]");
      if (last) {
        node[index] = value;
      } else {
        node.reset(node[index]);
      }
    }
    if (ok) diag.add_override(resolved, text);
  }
}

}  // namespace detail
}  // namespace sadr::orchestrator
