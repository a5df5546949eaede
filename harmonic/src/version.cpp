// The harmonic module's sources are globbed; this file keeps the library non-empty until the
// first algorithm lands.
namespace surfcomp::harmonic {
int module_version() { return 1; }
}  // namespace surfcomp::harmonic
