"""Writes docs/cases/semi_raos.csv: a PLAUSIBLE semisubmersible's displacement RAOs at its
reference point (the still water line at its centre), written for the fatigue study of issue 50
(docs/guide/design.md, "Fatigue over a scatter diagram"). Not a diffraction analysis of any hull:
closed forms with a semisubmersible's usual numbers, so that the vessel's motion has the right
order of magnitude and trend with period. The project had no RAO table; replace this one with
your vessel's (the format: docs/guide/waves.md, "The vessel on its RAOs").

  heave  |H| = e^{-k d_p} / sqrt((1 - r^2)^2 + (2 zeta r)^2),  r = f / f_h,  lag atan2(2 zeta r, 1 - r^2)
         (natural period 20 s, zeta 0.3 with the viscous damping of the columns and pontoons,
          the pontoons' depth d_p = 20 m attenuating the wave's pressure: 1.4 m/m at 20 s, 0.16 at 10 s)
  surge  |cos b| e^{-k d_s}, lag +90 deg for waves with a component along +x, -90 against
  sway   |sin b| e^{-k d_s}, likewise along +y          (the water particles' orbit, d_s = 10 m)
  pitch  0.3 k e^{-k d_p} |cos b| rad/m, lag 90 / -90    (0.3 of the wave slope: 0.3 deg/m at 10 s)
  roll   0.3 k e^{-k d_p} |sin b| rad/m, lag -90 / 90
  k = (2 pi f)^2 / g (deep water); b the waves' direction of travel (180: head seas for a bow along +x)

Frequencies 0.02 to 1.0 Hz every 0.02 (periods 1 to 50 s: the band 0.5/Tp to 4/Tp of a JONSWAP sea
with Tp from 4 to 25 s), directions 0, 90, 180, 270 and 360 deg.

    python docs/cases/semi_raos.py > docs/cases/semi_raos.csv
"""

import math

G = 9.81
F_HEAVE, ZETA, D_PONTOON, D_SURGE, PITCH_SLOPE = 0.05, 0.3, 20.0, 10.0, 0.3


def rows():
    freqs = [round(0.02 * i, 2) for i in range(1, 51)]
    for d in (0.0, 90.0, 180.0, 270.0, 360.0):
        c, s = math.cos(math.radians(d)), math.sin(math.radians(d))
        c = 0.0 if abs(c) < 1e-12 else c
        s = 0.0 if abs(s) < 1e-12 else s
        for f in freqs:
            k = (2 * math.pi * f) ** 2 / G
            r = f / F_HEAVE
            heave = math.exp(-k * D_PONTOON) / math.hypot(1 - r * r, 2 * ZETA * r)
            lag = math.degrees(math.atan2(2 * ZETA * r, 1 - r * r))
            horiz = math.exp(-k * D_SURGE)
            tilt = PITCH_SLOPE * k * math.exp(-k * D_PONTOON)
            yield "heave", f, d, heave, lag
            yield "surge", f, d, abs(c) * horiz, 90.0 if c >= 0 else -90.0
            yield "sway", f, d, abs(s) * horiz, 90.0 if s >= 0 else -90.0
            yield "pitch", f, d, abs(c) * tilt, 90.0 if c >= 0 else -90.0
            yield "roll", f, d, abs(s) * tilt, -90.0 if s >= 0 else 90.0


if __name__ == "__main__":
    print("# A plausible semisubmersible's displacement RAOs (synthetic: docs/cases/semi_raos.py says how;")
    print("# not a diffraction analysis). m/m and rad/m, phase: lag in deg, direction of travel in deg.")
    print("dof,frequency,direction,amplitude,phase")
    for dof, f, d, a, p in rows():
        print(f"{dof},{f!r},{d!r},{a:.6g},{p:.6g}")
