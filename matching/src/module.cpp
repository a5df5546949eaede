// The matching module's sources are globbed; this file keeps the library non-empty until the
// first algorithm lands (delete it then).
namespace surfcomp::matching {
int module_version() { return 1; }
}  // namespace surfcomp::matching
