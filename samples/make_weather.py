#!/usr/bin/env python3
"""Writes a synthetic EnergyPlus weather file (EPW) for trying `dynrad annual` without a
download: a year at a site near London (51.5 N, 0.12 W, UTC+0), each day clear, partly
cloudy or overcast in a fixed pseudo-random pattern (about a third each). Clear hours
follow Meinel's clear-sky beam, 1353 x 0.7^(AM^0.678) W/m2, with a diffuse tenth of the
beam's horizontal part plus 20 W/m2; partly cloudy hours keep 40% of the beam and twice
the diffuse; overcast hours have no beam and a diffuse of 25% of the clear global. The
illuminance fields are left missing (dynrad uses the Perez efficacy model). Not a
climate: for real studies take the site's EPW (climate.onebuilding.org, EnergyPlus).

usage: make_weather.py OUT.epw"""
import math
import sys


def sun(day, hour, lat=51.5, lon=-0.12, tz=0.0):
    """Zenith angle (degrees) at the middle of hour `hour` (1-24, ending) of day `day`."""
    g = 2 * math.pi / 365 * (day - 1 + (hour - 0.5 - 12) / 24)
    decl = (0.006918 - 0.399912 * math.cos(g) + 0.070257 * math.sin(g) - 0.006758 * math.cos(2 * g)
            + 0.000907 * math.sin(2 * g) - 0.002697 * math.cos(3 * g) + 0.00148 * math.sin(3 * g))
    eot = 229.18 * (0.000075 + 0.001868 * math.cos(g) - 0.032077 * math.sin(g) - 0.014615 * math.cos(2 * g)
                    - 0.040849 * math.sin(2 * g))
    minutes = (hour - 0.5) * 60 + eot + 4 * lon - 60 * tz
    ha = math.radians(minutes / 4 - 180)
    phi = math.radians(lat)
    c = math.sin(phi) * math.sin(decl) + math.cos(phi) * math.cos(decl) * math.cos(ha)
    return math.degrees(math.acos(max(-1.0, min(1.0, c))))


def main():
    out = sys.argv[1]
    days = [31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31]
    lines = [
        "LOCATION,Synthetic London,ENG,GBR,dynrad synthetic,999999,51.50,-0.12,0.0,11.0",
        "DESIGN CONDITIONS,0", "TYPICAL/EXTREME PERIODS,0", "GROUND TEMPERATURES,0",
        "HOLIDAYS/DAYLIGHT SAVINGS,No,0,0,0", "COMMENTS 1,synthetic weather for trying dynrad annual",
        "COMMENTS 2,not a climate", "DATA PERIODS,1,1,Data,Sunday, 1/ 1,12/31"]
    state = 12345
    day_of_year = 0
    for month in range(1, 13):
        for day in range(1, days[month - 1] + 1):
            day_of_year += 1
            state = (state * 1103515245 + 12345) % 2**31
            kind = state % 3  # 0 clear, 1 partly cloudy, 2 overcast
            for hour in range(1, 25):
                z = sun(day_of_year, hour)
                beam = diffuse = 0.0
                if z < 89.5:
                    am = 1 / (math.cos(math.radians(z)) + 0.50572 * (96.07995 - z) ** -1.6364)
                    clear = 1353 * 0.7 ** (am ** 0.678)
                    horizontal = clear * math.cos(math.radians(z))
                    clear_diffuse = 0.1 * horizontal + 20 * math.cos(math.radians(z)) ** 0.5
                    if kind == 0:
                        beam, diffuse = clear, clear_diffuse
                    elif kind == 1:
                        beam, diffuse = 0.4 * clear, 2 * clear_diffuse
                    else:
                        beam, diffuse = 0.0, 0.25 * (horizontal + clear_diffuse)
                glob = beam * max(0.0, math.cos(math.radians(z))) + diffuse
                fields = [2019, month, day, hour, 60, "?9?9?9?9E0?9?9?9?9?9?9?9?9?9?9?9?9?9?9?9*9*9?9?9?9",
                          12.0, 8.0, 75, 101325, 0, 0, 300, round(glob), round(beam), round(diffuse),
                          999999, 999999, 999999, 9999, 180, 3.0, 5, 5, 9999, 77777, 9, 999999999, 10, 0.1, 0, 88,
                          0.2, 0, 0]
                lines.append(",".join(str(f) for f in fields))
    with open(out, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
