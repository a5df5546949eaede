// The option tables: each option is defined once (an option of one name is the same in every
// table that offers it), its default lies in its domain and reads back from the text --help
// shows, and parsing and checking refuse what lies outside, naming the option in the spelling
// of the front end that installed one.
#include "surfcomp/core/option_table.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/option_names.hpp"
#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/matching/match_inputs.hpp"
#include "surfcomp/mesh/critical_points.hpp"
#include "surfcomp/mesh/surface.hpp"
#include "surfcomp/molsurf/load_surface.hpp"
#include "surfcomp/screening/library_build.hpp"
#include "surfcomp/screening/matrix.hpp"
#include "surfcomp/screening/screen.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

#include <cctype>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace surfcomp {
namespace {

/// One table's options as the user sees them, with their defaults.
struct Described {
  std::string table;
  std::vector<std::pair<options::Spec, options::Value>> options;
};

template <class Settings>
Described described(const std::string& name, const options::Table<Settings>& table) {
  const Settings defaults{};
  Described out{name, {}};
  for (const options::Option<Settings>& option : table)
    out.options.emplace_back(option.spec, option.get(defaults));
  return out;
}

std::vector<Described> every_table() {
  return {described("surface", molsurf::surface_input_option_table()),
          described("critical points", mesh::critical_point_option_table()),
          described("descriptors", harmonic::descriptor_option_table()),
          described("match", matching::match_option_table()),
          described("binding site", molsurf::binding_site_option_table()),
          described("describe", matching::describe_option_table()),
          described("pair match", matching::pair_match_option_table()),
          described("screen", screening::screen_option_table()),
          described("library build", screening::library_build_option_table()),
          described("matrix", screening::matrix_option_table())};
}

bool same_spec(const options::Spec& a, const options::Spec& b) {
  return a.name == b.name && a.kind == b.kind && a.help == b.help && a.unit == b.unit &&
         a.lo == b.lo && a.hi == b.hi && a.lo_open == b.lo_open && a.choices == b.choices &&
         a.optional == b.optional;
}

TEST(OptionTable, EachOptionIsDefinedOnceWithADefaultInItsDomain) {
  std::map<std::string, options::Spec> first;
  std::map<std::string, std::string> first_default;
  for (const Described& table : every_table()) {
    std::map<std::string, int> count;
    for (const auto& [spec, fallback] : table.options) {
      SCOPED_TRACE(table.table + ": --" + spec.name);
      EXPECT_EQ(++count[spec.name], 1) << "twice in one table";
      for (const char c : spec.name)
        EXPECT_TRUE(std::islower(static_cast<unsigned char>(c)) || c == '-' ||
                    std::isdigit(static_cast<unsigned char>(c)));
      EXPECT_FALSE(spec.help.empty());
      EXPECT_EQ(options::python_name(spec.name).find('-'), std::string::npos);
      // The same name means the same option, with the same default, in every table.
      const auto [known, inserted] = first.emplace(spec.name, spec);
      if (!inserted) {
        EXPECT_TRUE(same_spec(known->second, spec));
      }
      const auto [known_default, fresh] =
          first_default.emplace(spec.name, options::format(fallback));
      if (!fresh) {
        EXPECT_EQ(known_default->second, options::format(fallback));
      }
      if (spec.optional) continue;
      EXPECT_NO_THROW(options::check(spec, fallback, "--" + spec.name));
      // The default --help shows reads back as the default.
      if (spec.kind != options::Kind::flag && spec.kind != options::Kind::spheres) {
        EXPECT_EQ(options::parse(spec, options::format(fallback), "--" + spec.name), fallback);
      }
    }
  }
  EXPECT_GE(first.size(), 45u);  // every option of match, screen and hsi-build
}

TEST(OptionTable, ValuesOutsideTheDomainAreRefusedByName) {
  const auto refused = [](const options::Spec& spec, const std::string& text,
                          const std::string& expected) {
    try {
      options::parse(spec, text, "--" + spec.name);
      ADD_FAILURE() << "--" << spec.name << " " << text << " accepted";
    } catch (const OptionError& e) {
      EXPECT_EQ(std::string(e.what()), expected);
    }
  };
  const auto& surface = molsurf::surface_input_option_table();
  const options::Spec& probe = options::find(surface, "probe-radius")->spec;
  refused(probe, "-1", "--probe-radius: value -1 is outside [0, 10]");
  refused(probe, "nan", "--probe-radius: value nan is outside [0, 10]");
  refused(probe, "1.4x", "--probe-radius: '1.4x' is not a number");
  refused(options::find(surface, "charges")->spec, "best",
          "--charges: 'best' is not one of file|gasteiger|mmff");
  const auto& match = matching::match_option_table();
  refused(options::find(match, "rmsd-cut")->spec, "0", "--rmsd-cut: value 0 is outside (0, 100]");
  refused(options::find(match, "max-cliques")->spec, "2.5",
          "--max-cliques: '2.5' is not a whole number");
  refused(options::find(match, "max-cliques")->spec, "1.5e0",
          "--max-cliques: '1.5e0' is not a whole number");
  EXPECT_EQ(std::get<std::int64_t>(
                options::parse(options::find(match, "max-cliques")->spec, "1e3", "--max-cliques")),
            1000);
  refused(options::find(match, "principal-axes-starts")->spec, "5",
          "--principal-axes-starts: value 5 is not one of 0|4|24");
  const options::Spec sphere = molsurf::site_sphere_spec();
  refused(sphere, "1,2,3", "--site-sphere '1,2,3': expected x,y,z,r with r > 0 (A)");
  refused(sphere, "1,2,3,0", "--site-sphere '1,2,3,0': expected x,y,z,r with r > 0 (A)");
  const options::Value spheres = options::parse(sphere, " 1, 2,3 ,4", "--site-sphere");
  EXPECT_EQ(std::get<std::vector<options::Sphere>>(spheres),
            (std::vector<options::Sphere>{{1, 2, 3, 4}}));
}

TEST(OptionTable, SettingAnOptionSetsTheLibrarysField) {
  matching::PairMatchOptions settings;
  const auto& table = matching::pair_match_option_table();
  const auto set = [&](const std::string& name, const std::string& text) {
    const options::Option<matching::PairMatchOptions>* option = options::find(table, name);
    ASSERT_NE(option, nullptr) << name;
    option->set(settings, options::parse(option->spec, text, "--" + name));
  };
  set("probe-radius", "1.2");
  set("charges", "mmff");
  set("ranking", "vote");
  set("max-cliques", "7");
  set("site-sphere", "1,2,3,4");
  set("threads", "3");
  EXPECT_EQ(settings.inputs.input.surface.ses.probe_radius, 1.2);
  EXPECT_EQ(settings.inputs.input.read.charges, io::ChargeModel::mmff);
  EXPECT_EQ(settings.inputs.match.ranking.scheme, matching::ConsensusScheme::rank_by_vote);
  EXPECT_EQ(settings.inputs.match.max_cliques, 7u);
  ASSERT_EQ(settings.sites.spheres.size(), 1u);
  EXPECT_EQ(settings.sites.spheres[0].radius, 4.0);
  EXPECT_EQ(settings.inputs.threads, 3);
  EXPECT_EQ(options::find(table, "weights"), nullptr);  // hsi-build's, not match's
}

TEST(OptionTable, LibraryBuildConformersAndSeedShareTheirOptionalSettings) {
  const auto& table = screening::library_build_option_table();
  screening::LibraryBuildOptions options;
  const auto set = [&](const std::string& name, const std::string& text) {
    const auto* option = options::find(table, name);
    option->set(options, options::parse(option->spec, text, "--" + name));
  };
  set("seed", "7");  // without --conformers the seed has nothing to seed
  EXPECT_FALSE(options.conformers);
  set("conformers", "4");
  set("seed", "7");
  ASSERT_TRUE(options.conformers);
  EXPECT_EQ(options.conformers->count, 4);
  EXPECT_EQ(options.conformers->seed, 7);
  set("conformers", "0");
  EXPECT_FALSE(options.conformers);
}

TEST(OptionTable, TheLibraryChecksItsOptionsWithTheTablesRanges) {
  matching::MatchOptions options;
  options.overlay.sigma = 0.05;  // finite and > 0, but below the option's 0.1 A
  const auto validate = [&options] { matching::validate(options); };
  EXPECT_EQ(test::error_of(validate), "overlay_sigma: value 0.05 is outside [0.1, 10]");
  const options::ScopedSpelling command_line(&options::command_line_spelling);
  EXPECT_EQ(test::error_of(validate), "--overlay-sigma: value 0.05 is outside [0.1, 10]");
}

std::string shouted(const std::string& field) { return "<" + field + ">"; }

TEST(OptionNames, MessagesNameTheFieldInTheFrontEndsSpelling) {
  EXPECT_EQ(options::command_line_spelling("max_grid_cells"), "--max-grid-cells");
  EXPECT_EQ(options::command_line_spelling("unit"), "--unit");
  // A face that repeats a vertex: the message points to the repair option.
  Eigen::MatrixX3d positions(3, 3);
  positions << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  Eigen::MatrixX3i faces(1, 3);
  faces << 0, 1, 1;
  const auto build = [&] { mesh::Surface::from_arrays(positions, faces, "t"); };
  const auto message = [&](options::Spelling spelling) {
    const options::ScopedSpelling installed(spelling);
    return test::error_of(build);
  };
  EXPECT_NE(message(nullptr).find("(repair removes degenerate faces)"), std::string::npos)
      << message(nullptr);
  EXPECT_NE(message(&options::command_line_spelling).find("(--repair removes"), std::string::npos)
      << message(&options::command_line_spelling);
  EXPECT_NE(message(&shouted).find("(<repair> removes"), std::string::npos) << message(&shouted);
  EXPECT_EQ(options::spelling()("x"), "x");  // each installed spelling was taken back
  // Overlapping scopes: the first installs, the last to end restores what was there before.
  auto outer = std::make_unique<options::ScopedSpelling>(&options::command_line_spelling);
  auto inner = std::make_unique<options::ScopedSpelling>(&shouted);
  EXPECT_EQ(options::named("unit"), "--unit");
  outer.reset();
  EXPECT_EQ(options::named("unit"), "--unit");
  inner.reset();
  EXPECT_EQ(options::named("unit"), "unit");
}

}  // namespace
}  // namespace surfcomp
