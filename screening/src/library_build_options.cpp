#include "surfcomp/screening/library_build.hpp"

#include "surfcomp/molsurf/load_surface.hpp"

namespace surfcomp::screening {

const options::Table<LibraryBuildOptions>& library_build_option_table() {
  using options::Kind;
  using L = LibraryBuildOptions;
  static const options::Table<L> table = [] {
    // Both options live in the optional ConformerOptions: --conformers 0 leaves it unset (the
    // records' own coordinates), and --seed, applied after it, only matters when it is set.
    options::Table<L> t = {
        {{"conformers", Kind::integer,
          "conformers per molecule from ETKDG + MMFF (0: the records' own coordinates)", "", 0,
          10000},
         [](const L& l) {
           return options::Value(std::int64_t{l.conformers ? l.conformers->count : 0});
         },
         [](L& l, const options::Value& v) {
           const auto count = static_cast<int>(std::get<std::int64_t>(v));
           if (count == 0) {
             l.conformers.reset();
           } else {
             if (!l.conformers) l.conformers = ConformerOptions{};
             l.conformers->count = count;
           }
         }},
        {{"seed", Kind::integer, "ETKDG's random seed (with {conformers})", "", 0, 2147483647.0},
         [](const L& l) {
           return options::Value(
               std::int64_t{l.conformers ? l.conformers->seed : ConformerOptions{}.seed});
         },
         [](L& l, const options::Value& v) {
           if (l.conformers) l.conformers->seed = static_cast<int>(std::get<std::int64_t>(v));
         }},
        options::field<L>(
            {"shard-records", Kind::integer,
             "input records per shard: more make an index and a folder of shards", "", 1,
             2147483647.0},
            [](auto& l) -> auto& { return l.shard_records; }),
        options::field<L>(
            {"resume", Kind::flag,
             "continue the interrupted sharded build of the same output, inputs "
             "and options, keeping its finished shards"},
            [](auto& l) -> auto& { return l.resume; }),
    };
    // --repair as every subcommand that reads a mesh defines it.
    for (const auto& option : molsurf::surface_input_option_table()) {
      if (option.spec.name == "repair")
        t.push_back(options::field<L>(
            option.spec, [](auto& l) -> auto& { return l.repair; }));
    }
    t.push_back(options::field<L>(
        io::min_plddt_spec(), [](auto& l) -> auto& { return l.read.min_plddt; }));
    options::append(
        t, molsurf::binding_site_option_table(), [](auto& l) -> auto& { return l.site; });
    options::append(
        t, molsurf::pocket_option_table(), [](auto& l) -> auto& { return l.pockets; });
    return t;
  }();
  return table;
}

}  // namespace surfcomp::screening
