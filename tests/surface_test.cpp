#include "surfcomp/mesh/surface.hpp"

#include "surfcomp/core/error.hpp"

#include <gtest/gtest.h>

#include <iostream>
#include <sstream>
#include <string>

namespace surfcomp::mesh {
namespace {

TEST(SurfaceFromArrays, RejectedFacesThrowWithoutWritingToStderr) {
  // Three triangles on one edge: the third cannot join a manifold half-edge mesh.
  Eigen::MatrixX3d p(5, 3);
  p << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1;
  Eigen::MatrixX3i f(3, 3);
  f << 0, 1, 2, 1, 0, 3, 0, 1, 4;
  std::ostringstream captured;
  std::streambuf* const saved = std::cerr.rdbuf(captured.rdbuf());
  try {
    Surface::from_arrays(p, f, "fin");
    ADD_FAILURE() << "a complex edge was accepted";
  } catch (const TopologyError& e) {
    EXPECT_NE(std::string(e.what()).find("fin: face 2"), std::string::npos) << e.what();
  }
  std::cerr.rdbuf(saved);
  EXPECT_EQ(captured.str(), "");
}

}  // namespace
}  // namespace surfcomp::mesh
