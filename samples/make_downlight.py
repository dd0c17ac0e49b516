#!/usr/bin/env python3
"""Writes samples/downlight.ies: a recessed LED downlight's photometry in IES LM-63-2002
form, made up for the samples (no manufacturer's data): axially symmetric, intensity
I(gamma) = I0 cos(gamma)^1.4 fading to nothing between 55 and 65 degrees, scaled so that
the luminaire sends 85% of its 3000 lm lamp (2550 lm). Run from the repository root."""
import math
import os

LAMP_LUMENS = 3000.0
LOR = 0.85
GAMMAS = list(range(0, 91, 5))


def shape(g):
    c = math.cos(math.radians(g)) ** 1.4
    if g <= 55:
        return c
    if g >= 65:
        return 0.0
    t = (65 - g) / 10.0
    return c * t * t * (3 - 2 * t)


def flux_of(scale):
    # 2 pi integral of I(gamma) sin(gamma), fine midpoint rule on the smooth shape.
    n = 9000
    h = math.radians(90) / n
    return 2 * math.pi * scale * sum(shape(math.degrees((i + 0.5) * h)) * math.sin((i + 0.5) * h) for i in range(n)) * h


def main():
    i0 = LOR * LAMP_LUMENS / flux_of(1.0)
    lines = [
        "IESNA:LM-63-2002",
        "[TEST] dynrad sample, made up by samples/make_downlight.py",
        "[MANUFAC] dynrad samples",
        "[LUMCAT] DL-3000",
        "[LUMINAIRE] recessed LED downlight, 3000 lm lamp, 85% light output ratio",
        "[LAMP] LED module 3000 lm",
        "TILT=NONE",
        # lamps, lumens per lamp, multiplier, vertical angles, horizontal angles,
        # photometric type C, metres, width, length, height (negative: round, 0.15 m)
        f"1 {LAMP_LUMENS:.0f} 1 {len(GAMMAS)} 1 1 2 -0.15 -0.15 0",
        "1 1 18",
        " ".join(str(g) for g in GAMMAS),
        "0",
        " ".join(f"{i0 * shape(g):.2f}" for g in GAMMAS),
    ]
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "downlight.ies")
    with open(path, "w", encoding="ascii", newline="\r\n") as out:
        out.write("\n".join(lines) + "\n")
    print(f"wrote {path}: I0 = {i0:.1f} cd, {LOR * LAMP_LUMENS:.0f} lm")


if __name__ == "__main__":
    main()
