#pragma once
// Gmsh .geo text of an axis-aligned rectangle, the brick of the tests' hand-made geometries.
#include <string>

namespace rockdd::test {

/// Gmsh lines for an axis-aligned rectangle [x0, x1] x [y0, y1] of element size `size`, as
/// surface `id` (points, lines and loop numbered id + 1 .. id + 4): bottom is line id + 1,
/// right id + 2, top id + 3, left id + 4.
inline std::string rectangle_geo(int id, double x0, double y0, double x1, double y1, double size) {
  auto num = [](double v) { return std::to_string(v); };
  auto n = [&](int k) { return std::to_string(id + k); };
  const std::string s = num(size);
  return "Point(" + n(1) + ") = {" + num(x0) + ", " + num(y0) + ", 0, " + s + "};\n" + "Point(" +
         n(2) + ") = {" + num(x1) + ", " + num(y0) + ", 0, " + s + "};\n" + "Point(" + n(3) +
         ") = {" + num(x1) + ", " + num(y1) + ", 0, " + s + "};\n" + "Point(" + n(4) + ") = {" +
         num(x0) + ", " + num(y1) + ", 0, " + s + "};\n" + "Line(" + n(1) + ") = {" + n(1) + ", " +
         n(2) + "};\nLine(" + n(2) + ") = {" + n(2) + ", " + n(3) + "};\nLine(" + n(3) + ") = {" +
         n(3) + ", " + n(4) + "};\nLine(" + n(4) + ") = {" + n(4) + ", " + n(1) + "};\n" +
         "Curve Loop(" + n(1) + ") = {" + n(1) + ", " + n(2) + ", " + n(3) + ", " + n(4) +
         "};\nPlane Surface(" + n(1) + ") = {" + n(1) + "};\n";
}

}  // namespace rockdd::test
