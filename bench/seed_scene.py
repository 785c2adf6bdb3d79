"""The seed scene (edp/hertz.edp's defaults) and Hertz's answer for it, for the peers of
make bench (each a script run by its own Python: this module sits beside them)."""
import math

E, NU, R, D = 10.0, 0.3, 0.5, 0.02
A_H = math.sqrt(R * D)
E_STAR = E / (1 - NU**2)
F_H = 4.0 / 3.0 * E_STAR * A_H * D
P0_H = 3 * F_H / (2 * math.pi * A_H**2)
