"""Closed-form solutions of the paper's benchmarks, shared by tools/plot, tests and reports.

Units are SI throughout; stresses are tension positive (the engine's convention).
Every function accepts NumPy arrays or plain floats.
"""

import numpy as np


def timoshenko_cantilever_deflection(x, L=0.04, h=0.01, t=1.0, P=1e4, E=10e9, nu=0.3, kappa=5.0 / 6.0):
    """Downward deflection v(x) of a cantilever clamped at x = 0 with a tip load P at x = L.

    Bending plus shear (Timoshenko):  v = P x^2 (3L - x) / (6 E I) + P x / (kappa G A),
    with I = t h^3 / 12, A = t h and the plane-stress shear modulus G = E / (2 (1 + nu)).
    """
    x = np.asarray(x, dtype=float)
    I = t * h**3 / 12.0
    A = t * h
    G = E / (2.0 * (1.0 + nu))
    return P * x**2 * (3.0 * L - x) / (6.0 * E * I) + P * x / (kappa * G * A)


def huang_brazilian_stresses(y, R=0.025, alpha=np.radians(10.0), t=1.0, P=1.0):
    """(sigma_x, sigma_y) on the loaded diameter of a flattened Brazilian disc, Huang et al. (2015).

    The paper's eqs. (15)-(16); y runs along the loaded diameter from the centre, alpha is
    the half-angle of the flat ends, P the total load, tension positive:
      A1,2 = (R cos a +- y)^2 + (R sin a)^2,  B1,2 = (R cos a +- y) R sin a,
      C1,2 = -atan(R sin a / (R cos a +- y)),
      sigma_x =  P/(pi R t sin a) (B1/A1 + C1 + B2/A2 + C2) + P cos a/(pi R t),
      sigma_y = -P/(pi R t sin a) (B1/A1 - C1 + B2/A2 - C2) + P cos a/(pi R t).
    atan is taken as atan2 so that C stays continuous past |y| = R cos a; inside the
    flattened disc (|y| <= R cos a) the two are the same.
    At the centre sigma_x = P/(pi R t) (3 cos a - 2 a / sin a) and
    sigma_y = -P/(pi R t) (cos a + 2 a / sin a): for a -> 0 the point-load values +1 and -3.
    """
    y = np.asarray(y, dtype=float)
    c, s = R * np.cos(alpha), R * np.sin(alpha)
    A1, A2 = (c + y) ** 2 + s**2, (c - y) ** 2 + s**2
    B1, B2 = (c + y) * s, (c - y) * s
    C1, C2 = -np.arctan2(s, c + y), -np.arctan2(s, c - y)
    k = P / (np.pi * R * t * np.sin(alpha))
    uniform = P * np.cos(alpha) / (np.pi * R * t)
    sigma_x = k * (B1 / A1 + C1 + B2 / A2 + C2) + uniform
    sigma_y = -k * (B1 / A1 - C1 + B2 / A2 - C2) + uniform
    return sigma_x, sigma_y


def sliding_block_displacement(time, theta=np.radians(30.0), g=10.0, friction_angle=0.0):
    """(u_x, u_y) magnitudes of a block sliding from rest down a plane inclined at theta.

    Frictionless (the paper's case): u_x = 1/2 g cos(th) sin(th) t^2, u_y = 1/2 g sin(th)^2 t^2,
    u_x horizontal down-slope and u_y downward. With a friction angle phi the acceleration
    along the slope is g (sin th - cos th tan phi), and zero when that is negative (the block sticks).
    """
    time = np.asarray(time, dtype=float)
    along = max(g * (np.sin(theta) - np.cos(theta) * np.tan(friction_angle)), 0.0)
    distance = 0.5 * along * time**2
    return distance * np.cos(theta), distance * np.sin(theta)


def kirsch_axis_stress(y, a=1.0, S=1.0):
    """sigma_xx on the axis x = 0 (across the load) of an infinite plate with a circular hole
    of radius a under remote uniaxial tension S along x, for |y| >= a.

    Kirsch (1898); e.g. Timoshenko & Goodier, Theory of Elasticity, section 35:
      sigma_theta(r, theta = 90 deg) = S/2 (2 + a^2/r^2 + 3 a^4/r^4),
    so 3 S at the edge of the hole (stress concentration factor 3) and S far away.
    """
    r = np.abs(np.asarray(y, dtype=float))
    return 0.5 * S * (2.0 + a**2 / r**2 + 3.0 * a**4 / r**4)


def lame_cylinder(r, a=0.1, b=0.2, p=100e6, E=200e9, nu=0.3):
    """(u_r, sigma_r, sigma_theta) at radius r of a thick-walled cylinder (bore a, outside b)
    under internal pressure p, plane stress, tension positive.

    Lame (1852); e.g. Timoshenko & Goodier, section 28:
      sigma_r = A - B/r^2,  sigma_theta = A + B/r^2,
      A = p a^2 / (b^2 - a^2),  B = p a^2 b^2 / (b^2 - a^2),
      u_r = ((1 - nu) A r + (1 + nu) B / r) / E   (plane stress),
    so at the bore u_r(a) = p a ((1 - nu) a^2 + (1 + nu) b^2) / (E (b^2 - a^2)).
    """
    r = np.asarray(r, dtype=float)
    A = p * a**2 / (b**2 - a**2)
    B = p * a**2 * b**2 / (b**2 - a**2)
    return ((1.0 - nu) * A * r + (1.0 + nu) * B / r) / E, A - B / r**2, A + B / r**2


def column_own_weight(y, L=1.0, rho=2600.0, g=10.0, E=1e9):
    """(u_y, sigma_yy) at height y of a column of height L standing on rollers at y = 0 under
    its own weight (gravity -g along y), uniaxial (exact in 2-D for nu = 0):
      sigma_yy = -rho g (L - y),   u_y = -rho g (2 L y - y^2) / (2 E).
    """
    y = np.asarray(y, dtype=float)
    return -rho * g * (2.0 * L * y - y**2) / (2.0 * E), -rho * g * (L - y)


def free_fall(time, g=10.0):
    """(u_y, v_y) of a body released from rest under gravity -g: -1/2 g t^2 and -g t."""
    time = np.asarray(time, dtype=float)
    return -0.5 * g * time**2, -g * time


def rigid_rotation_displacement(point, centre, angle):
    """Displacement (R(angle) - I)(point - centre) of a point of a body turned rigidly by
    `angle` (counter-clockwise, rad) about `centre`; for a spin at omega, angle = omega t."""
    rx, ry = point[0] - centre[0], point[1] - centre[1]
    c, s = np.cos(angle), np.sin(angle)
    return c * rx - s * ry - rx, s * rx + c * ry - ry


def mohr_coulomb_ucs(cohesion, friction_angle):
    """Uniaxial compressive strength of the Mohr-Coulomb criterion (METHOD.md, shear damage):
      fc0 = 2 c cos(phi) / (1 - sin(phi)),
    the axial stress at which c1 - c3 (1 + sin phi)/(1 - sin phi) reaches fc0 with c3 = 0.
    friction_angle in radians.
    """
    return 2.0 * cohesion * np.cos(friction_angle) / (1.0 - np.sin(friction_angle))


def mohr_coulomb_confined(cohesion, friction_angle, confinement):
    """Major principal stress at which the Mohr-Coulomb criterion (METHOD.md, shear damage)
    starts with the minor principal stress c3 = confinement (compression positive):
      c1 = fc0 + c3 (1 + sin(phi)) / (1 - sin(phi)).
    friction_angle in radians.
    """
    k = (1.0 + np.sin(friction_angle)) / (1.0 - np.sin(friction_angle))
    return mohr_coulomb_ucs(cohesion, friction_angle) + confinement * k


def hondros_centre_stresses(p, alpha):
    """(sigma_x, sigma_y) at the centre of a disk loaded by a uniform radial pressure p on two
    opposite arcs of half-angle alpha (rad) about the y axis, tension positive.

    Hondros (1959), exact in plane elasticity:
      sigma_x = (2 p / pi) (sin 2a - a),   sigma_y = -(2 p / pi) (sin 2a + a);
    the total load is P = 2 p R sin(a) t, so sigma_x = P/(pi R t) (2 cos a - a / sin a),
    against the flattened disk's P/(pi R t) (3 cos a - 2 a / sin a) (huang_brazilian_stresses).
    """
    return 2.0 * p / np.pi * (np.sin(2.0 * alpha) - alpha), -2.0 * p / np.pi * (np.sin(2.0 * alpha) + alpha)
