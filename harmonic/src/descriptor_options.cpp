#include "surfcomp/harmonic/surface_descriptors.hpp"

namespace surfcomp::harmonic {

const options::Table<DescriptorOptions>& descriptor_option_table() {
  using options::Kind;
  using D = DescriptorOptions;
  static const options::Table<D> table = [] {
    options::Table<D> t;
    options::append(
        t, mesh::critical_point_option_table(), [](auto& d) -> auto& { return d.critical_points; });
    options::Table<D> own = {
        options::field<D>(
            {"patch-radius", Kind::real,
             "patch radius (on-surface); about 5 for ligands, larger for protein sites", "A", 0.1,
             100.0},
            [](auto& d) -> auto& { return d.patch.radius; }),
        options::field<D>(
            {"image-rings", Kind::integer, "image grid: rings of the polar grid", "", 1, 1024},
            [](auto& d) -> auto& { return d.image.rings; }),
        options::field<D>(
            {"image-sectors", Kind::integer,
             "image grid: sectors (samples per ring; 180 = 2-degree rotation steps)", "", 1, 4096},
            [](auto& d) -> auto& { return d.image.sectors; }),
        options::choice<D>(
            {"weights", Kind::choice, "harmonic map spring weights (inverse-length: the seed's)"},
            [](auto& d) -> auto& { return d.disk_map.weights; }, spring_weights_names),
        options::field<D>(
            {"max-image-bytes", Kind::integer, "limit: memory of the shape images", "bytes", 1,
             1e15},
            [](auto& d) -> auto& { return d.max_image_bytes; }),
    };
    t.insert(t.end(), own.begin(), own.end());
    return t;
  }();
  return table;
}

}  // namespace surfcomp::harmonic
