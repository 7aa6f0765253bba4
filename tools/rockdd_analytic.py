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
