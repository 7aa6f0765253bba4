#pragma once
// Principal values of symmetric 2x2 tensors (in-plane stress or strain).

namespace rockdd::kernels {

/// In-plane principal values of a stress-like tensor {xx, yy, xy}: p1 >= p2.
void principal_values(double xx, double yy, double xy, double& p1, double& p2);

/// Angle (rad, counter-clockwise from x) of the direction of p1.
double principal_angle(double xx, double yy, double xy);

/// Principal values of an engineering strain {exx, eyy, gxy} (gxy = 2 exy): e1 >= e2.
void principal_strains(const double eps[3], double& e1, double& e2);

}  // namespace rockdd::kernels
