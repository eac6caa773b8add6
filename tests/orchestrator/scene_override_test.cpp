// SPDX-License-Identifier: MIT
// Scene overrides (--set PATH=VALUE): syntax, resolution by key, name and
// index, validation by the loader with messages naming the override, and the
// hash of the effective scene.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "sadr/common/status.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "sadr/orchestrator/scene_override.hpp"
#include "scene_test_support.hpp"

namespace sadr::orchestrator {
namespace {

using test::kBaseScene;

/// The base scene with a named reaction (list items by name).
const std::string kNamed = test::replace_once(kBaseScene, "  - {equation: \"A -> 0\", rate: 1.0}",
                                              "  - {name: decay, equation: \"A -> 0\", rate: 1.0}");

Scene with(const std::vector<std::string>& sets, const std::string& text = kNamed) {
  return parse_scene(text, "scene.yaml", parse_overrides(sets));
}

std::string error_of(const std::vector<std::string>& sets) {
  try {
    with(sets);
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SceneOverride, ParsesPathAndValueAtTheFirstEquals) {
  const SceneOverride o = parse_override("output.times=[0.1, 0.2]");
  EXPECT_EQ(o.path, "output.times");
  EXPECT_EQ(o.value, "[0.1, 0.2]");
  EXPECT_EQ(parse_override("a.b=x=y").value, "x=y");
  EXPECT_EQ(o.text(), "output.times=[0.1, 0.2]");
}

TEST(SceneOverride, RejectsBadSyntaxNamingTheText) {
  for (const char* bad : {"fluid.sound_speed", "=3", "a..b=1", "a.=1", "[0].x=1", "a[0=1", "a[]=1",
                          "a[0]b=1", "a]=1"}) {
    try {
      parse_override(bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("--set '") + bad + "'"), std::string::npos)
          << e.what();
    }
  }
}

TEST(SceneOverride, SetsMapKeysListItemsByNameAndByIndex) {
  const Scene s = with({"reactions[decay].rate=0.25", "species[1].diffusivity=0.5", "time.end=0.5",
                        "ssa.regularization=0.02"});
  EXPECT_EQ(s.reactions.at(0).rate, 0.25);
  EXPECT_EQ(s.species.at(1).diffusivity, 0.5);
  EXPECT_EQ(s.time.end, 0.5);
  EXPECT_EQ(s.ssa.regularization, 0.02);  // a section absent from the file is added
  EXPECT_EQ(s.overrides,
            (std::vector<std::string>{"reactions[decay].rate=0.25", "species[1].diffusivity=0.5",
                                      "time.end=0.5", "ssa.regularization=0.02"}));
}

TEST(SceneOverride, LaterOverridesWinAndValuesAreYaml) {
  const Scene s = with({"time.end=0.3", "time.end=0.7", "output={times: [0.2, 0.4]}"});
  EXPECT_EQ(s.time.end, 0.7);
  EXPECT_EQ(s.output.times, (std::vector<double>{0.0, 0.2, 0.4, 0.7}));
}

TEST(SceneOverride, InvalidValuesAreReportedByTheLoaderNamingTheOverride) {
  const std::string e = error_of({"reactions[decay].rate=abc", "fluid.sound_sped=3"});
  EXPECT_NE(e.find("reactions[0].rate: 'abc' is not a number"), std::string::npos) << e;
  EXPECT_NE(e.find("(set by --set reactions[decay].rate=abc)"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown key 'sound_sped' in fluid; did you mean 'sound_speed'?"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("(set by --set fluid.sound_sped=3)"), std::string::npos) << e;
  EXPECT_EQ(e.find("scene.yaml:1:1"), std::string::npos) << "no file position for a --set: " << e;
  const std::string range = error_of({"time.end=-1"});
  EXPECT_NE(range.find("time.end: -1 is out of range"), std::string::npos) << range;
  EXPECT_NE(range.find("(set by --set time.end=-1)"), std::string::npos) << range;
}

TEST(SceneOverride, UnresolvablePathsNameTheOverrideAndTheCandidates) {
  const std::string name = error_of({"reactions[decai].rate=1"});
  EXPECT_NE(name.find("--set reactions[decai].rate=1: no item named 'decai' in 'reactions'; "
                      "did you mean 'decay'?"),
            std::string::npos)
      << name;
  const std::string index = error_of({"species[5].diffusivity=1"});
  EXPECT_NE(index.find("index 5 is out of range: 'species' has 2 items (0..1)"), std::string::npos)
      << index;
  const std::string scalar = error_of({"time.end.x=1"});
  EXPECT_NE(scalar.find("'time.end' is the value '1.0', not a map with key 'x'"), std::string::npos)
      << scalar;
  const std::string list = error_of({"time[0]=1"});
  EXPECT_NE(list.find("'time' is a map, not a list"), std::string::npos) << list;
  const std::string yaml = error_of({"time.end=[1"});
  EXPECT_NE(yaml.find("--set time.end=[1: the value is not valid YAML"), std::string::npos) << yaml;
}

TEST(SceneOverride, HashIsThatOfTheEffectiveScene) {
  const Scene plain = with({});
  EXPECT_TRUE(plain.overrides.empty());
  const Scene a = with({"time.end=0.5"});
  const Scene b = with({"time.end=0.5"});
  const Scene c = with({"time.end=0.6"});
  EXPECT_EQ(a.source_hash, b.source_hash);
  EXPECT_NE(a.source_hash, plain.source_hash);
  EXPECT_NE(a.source_hash, c.source_hash);
  // Same value as in the file: the same scene, but a different hash (the hash
  // covers the file and the overrides as written).
  const Scene same = with({"time.end=1.0"});
  EXPECT_EQ(same.time.end, plain.time.end);
}

}  // namespace
}  // namespace sadr::orchestrator
