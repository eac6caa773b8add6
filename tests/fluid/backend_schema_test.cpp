// SPDX-License-Identifier: MIT
// Unit: the backend schema (sadr/fluid/backend_schema.hpp) against the backends it describes and
// against docs/scene-format.md.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>

#include "sadr/fluid/backend_schema.hpp"
#include "sadr/fluid/builtin_backends.hpp"
#include "sadr/fluid/kernel.hpp"
#include "tdpd/tdpd_backend.hpp"

namespace sadr::fluid {
namespace {

// One entry per registered backend, in the same order; a backend's capabilities are its entry's.
TEST(BackendSchema, DescribesEveryRegisteredBackend) {
  BackendRegistry reg;
  register_builtin_backends(reg);
  std::vector<std::string> names;
  for (const auto& b : schema::backends()) names.push_back(b.name);
  EXPECT_EQ(names, reg.names());
  for (const auto& d : schema::backends()) {
    const auto backend = reg.create(d.name);
    EXPECT_EQ(backend->name(), d.name);
    EXPECT_EQ(&backend->capabilities(), &schema::find(d.name)->capabilities) << d.name;
    ASSERT_FALSE(d.capabilities.kernels.empty()) << d.name;
    ASSERT_FALSE(d.capabilities.wall_models.empty()) << d.name;
    for (const auto& k : d.capabilities.kernels) EXPECT_NO_THROW((void)parse_kernel(k)) << k;
    for (const auto& p : d.parameters) {
      std::string why;
      EXPECT_TRUE(p.allows(p.default_value, why)) << d.name << "." << p.name << ": " << why;
      EXPECT_FALSE(p.doc.empty()) << d.name << "." << p.name;
    }
  }
}

// The schema's defaults are the code's defaults.
TEST(BackendSchema, DefaultsAreTheBackendsDefaults) {
  const FluidModel m;
  const auto* sdpd = schema::find("sdpd");
  ASSERT_NE(sdpd, nullptr);
  EXPECT_EQ(sdpd->parameter("density_diffusion")->default_value, m.density_diffusion);
  EXPECT_EQ(sdpd->parameter("diffusion_eps")->default_value, m.diffusion_eps);
  EXPECT_EQ(sdpd->parameter("density_band")->default_value, m.density_band);
  EXPECT_EQ(sdpd->parameter("neighbor_skin")->default_value, m.neighbor_skin);
  EXPECT_EQ(schema::find("static")->parameter("diffusion_eps")->default_value, m.diffusion_eps);
  const TdpdParameters t;
  const auto* td = schema::find("tdpd");
  ASSERT_NE(td, nullptr);
  EXPECT_EQ(td->parameter("a")->default_value, t.a);
  EXPECT_EQ(td->parameter("gamma")->default_value, t.gamma);
  EXPECT_EQ(td->parameter("s1")->default_value, t.s1);
  EXPECT_EQ(td->parameter("r_cc")->default_value, t.r_cc);
  EXPECT_EQ(td->parameter("lambda")->default_value, t.lambda);
  EXPECT_EQ(td->parameter("skin")->default_value, t.skin);
  EXPECT_EQ(td->parameter("neighbor_skin")->default_value, m.neighbor_skin);
  EXPECT_EQ(td->parameter("effective_walls")->default_value, t.effective_walls ? 1.0 : 0.0);
  EXPECT_EQ(td->parameter("buffer_axis")->default_value, t.buffer_axis);
  EXPECT_EQ(td->parameter("inflow_length")->default_value, t.inflow_length);
  EXPECT_EQ(td->parameter("inflow_value")->default_value, t.inflow_value);
  // every tdpd parameter but the model's neighbor_skin is a name TdpdParameters::apply knows
  for (const auto& p : td->parameters) {
    if (p.name == "neighbor_skin") continue;
    TdpdParameters q;
    EXPECT_NO_THROW(q.apply({{p.name, p.default_value}})) << p.name;
  }
  std::string why;
  EXPECT_FALSE(td->parameter("lambda")->allows(1.5, why));
  EXPECT_EQ(why, "[0, 1]");
  EXPECT_FALSE(td->parameter("buffer_axis")->allows(0.5, why));
  EXPECT_EQ(why, "a whole number, [-1, 2]");
  EXPECT_FALSE(sdpd->parameter("density_band")->allows(0.0, why));
  EXPECT_EQ(why, "(0, 1)");
}

// docs/scene-format.md holds the tables `sadr backends --markdown` prints, verbatim.
TEST(BackendSchema, SceneFormatDocHasTheGeneratedTables) {
  std::ifstream in(std::string(SADR_SOURCE_DIR) + "/docs/scene-format.md");
  ASSERT_TRUE(in);
  const std::string doc{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  EXPECT_NE(doc.find(schema::markdown_capabilities()), std::string::npos)
      << "regenerate with `sadr backends --markdown`:\n"
      << schema::markdown_capabilities();
  for (const auto& b : schema::backends()) {
    const std::string table = "`" + b.name + "` parameters:\n\n" + schema::markdown_parameters(b);
    EXPECT_NE(doc.find(table), std::string::npos) << "regenerate with `sadr backends --markdown`:\n"
                                                  << table;
  }
}

}  // namespace
}  // namespace sadr::fluid
