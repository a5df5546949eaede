#include "surfcomp/matching/match_inputs.hpp"

namespace surfcomp::matching {

const options::Table<MatchInputOptions>& describe_option_table() {
  using I = MatchInputOptions;
  static const options::Table<I> table = [] {
    options::Table<I> t;
    options::append(
        t, molsurf::surface_input_option_table(), [](auto& i) -> auto& { return i.input; });
    options::append(
        t, harmonic::descriptor_option_table(), [](auto& i) -> auto& { return i.descriptors; });
    t.push_back(options::threads_option<I>([](auto& i) -> auto& { return i.threads; }));
    return t;
  }();
  return table;
}

const options::Table<PairMatchOptions>& pair_match_option_table() {
  using options::Kind;
  using P = PairMatchOptions;
  static const options::Table<P> table = [] {
    options::Table<P> t;
    options::append(
        t, molsurf::surface_input_option_table(), [](auto& p) -> auto& { return p.inputs.input; });
    options::append(
        t, harmonic::descriptor_option_table(),
        [](auto& p) -> auto& { return p.inputs.descriptors; },
        {"critical-point-radius", "disc-radius", "image-rings", "image-sectors", "weights"});
    options::append(
        t, match_option_table(), [](auto& p) -> auto& { return p.inputs.match; });
    const auto text = [](const char* name, const char* help) {
      return options::Spec{name, Kind::text, help, "", 0, 0, false, {}, true};
    };
    t.push_back(options::field<P>(
        molsurf::site_ligand_spec(), [](auto& p) -> auto& { return p.sites.ligand; }));
    t.push_back(options::field<P>(
        text("ref-site-ligand", "binding site of REF only"),
        [](auto& p) -> auto& { return p.sites.reference_ligand; }));
    t.push_back(options::field<P>(
        text("probe-site-ligand", "binding site of PROBE only"),
        [](auto& p) -> auto& { return p.sites.probe_ligand; }));
    t.push_back(molsurf::sphere_option<P>(
        molsurf::site_sphere_spec(), [](auto& p) -> auto& { return p.sites.spheres; }));
    t.push_back(molsurf::sphere_option<P>(
        {"ref-site-sphere", Kind::spheres, "site sphere on REF only", "A"},
        [](auto& p) -> auto& { return p.sites.reference_spheres; }));
    t.push_back(molsurf::sphere_option<P>(
        {"probe-site-sphere", Kind::spheres, "site sphere on PROBE only", "A"},
        [](auto& p) -> auto& { return p.sites.probe_spheres; }));
    t.push_back(options::field<P>(
        molsurf::site_pocket_spec(), [](auto& p) -> auto& { return p.sites.pocket; }));
    const auto pocket = [](const char* name, const char* help) {
      return options::Spec{name, Kind::integer, help, "", 1, 1e6, false, {}, true};
    };
    t.push_back(options::field<P>(
        pocket("ref-site-pocket", "binding site of REF only: its pocket N"),
        [](auto& p) -> auto& { return p.sites.reference_pocket; }));
    t.push_back(options::field<P>(
        pocket("probe-site-pocket", "binding site of PROBE only: its pocket N"),
        [](auto& p) -> auto& { return p.sites.probe_pocket; }));
    options::append(
        t, molsurf::binding_site_option_table(), [](auto& p) -> auto& { return p.inputs.site; });
    options::append(
        t, molsurf::pocket_option_table(), [](auto& p) -> auto& { return p.inputs.pockets; });
    t.push_back(options::threads_option<P>([](auto& p) -> auto& { return p.inputs.threads; }));
    return t;
  }();
  return table;
}

MatchInput with_site(MatchInput input, const PairSites& sites, bool reference) {
  const std::string& own = reference ? sites.reference_ligand : sites.probe_ligand;
  input.site_ligand = own.empty() ? sites.ligand : own;
  const int own_pocket = reference ? sites.reference_pocket : sites.probe_pocket;
  input.site_pocket = own_pocket != 0 ? own_pocket : sites.pocket;
  input.site_spheres.insert(input.site_spheres.end(), sites.spheres.begin(), sites.spheres.end());
  const auto& spheres = reference ? sites.reference_spheres : sites.probe_spheres;
  input.site_spheres.insert(input.site_spheres.end(), spheres.begin(), spheres.end());
  return input;
}

std::string site_ligand_option(const PairSites& sites, bool reference) {
  if (reference) {
    return options::named(sites.reference_ligand.empty() ? "site_ligand" : "ref_site_ligand");
  }
  return options::named(sites.probe_ligand.empty() ? "site_ligand" : "probe_site_ligand");
}

}  // namespace surfcomp::matching
