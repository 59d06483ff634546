#!/usr/bin/env python3
"""Would a rigorous cut of the refresh's elevation pass pay on the design member?

The refresh sums the elevation `eta` over every component because `eta` sets the
Wheeler evaluation depth `zs = h (z - eta) / (h + eta)`, and `zs` sets the decay of
the components the decay pass keeps (`src/sea/cut.rs`). Dropping the components
`i >= m` from the elevation moves `eta` by up to `E = sum_{i >= m} A_i` (a bound must
allow them all in phase), `zs` by `|dzs/deta| E` with `|dzs/deta| = h (z + h) /
(h + eta)^2` (taken at `eta = 0`: the most favourable), and the kept velocity by
`2 sum_kept k A_u e^{k zs} |dzs/deta| E` (`|d ch/dzs| = k |sh| <= 2 k e^{k zs}`), the
form of `cut.rs`'s bounds. Held under the same limit as the decay cut
(`CUT_FRACTION` 1e-2 x the cache tolerance 1e-3 x `sigma_u`, and the same with
`A_a` against `sigma_a`), with the kept components the decay cut's prefix at `zs = z`
(speed 0), this prints, per node height, the largest `E` allowed and the smallest `E`
a cut could drop (the last, shortest component's amplitude alone): where the first is
under the second, no component can leave the elevation pass. The rates' terms, the
decay cut's own shift and a finite speed only make the allowance smaller.

The sea: the member's JONSWAP (Hs 9 m, Tp 13 s, gamma 2.5, 320 m of water) split as
`sea::irregular::discretise` does (200 equal bins between 0.2% and 99.5% of the
energy, amplitude from each bin's energy); the frequency within each bin is its
middle here (the solver draws it), which moves each `k` by under half a bin.

    python3 scripts/elevation_cut_bound.py
"""
import math

G, H, HS, TP, GAMMA, N = 9.81, 320.0, 9.0, 13.0, 2.5, 200
TOL, CUT_FRACTION = 1e-3, 1e-2


def jonswap(w):
    wp = 2 * math.pi / TP
    pm = 5 / 16 * HS**2 * wp**4 / w**5 * math.exp(-1.25 * (wp / w) ** 4)
    s = 0.07 if w <= wp else 0.09
    r = math.exp(-((w - wp) ** 2) / (2 * s * s * wp * wp))
    return (1 - 0.287 * math.log(GAMMA)) * pm * GAMMA**r


def wave_number(w):
    k = w * w / G
    for _ in range(200):
        k = w * w / (G * math.tanh(k * H))
    return k


def components():
    m = 20000
    ws = [1e-3 + (6.0 - 1e-3) * i / m for i in range(m + 1)]
    c = [0.0]
    for i in range(m):
        c.append(c[-1] + 0.5 * (jonswap(ws[i]) + jonswap(ws[i + 1])) * (ws[i + 1] - ws[i]))

    def at(level):  # the frequency below which `level` of the energy lies
        j = next(i for i, v in enumerate(c) if v >= level)
        return ws[j - 1] + (level - c[j - 1]) / (c[j] - c[j - 1]) * (ws[j] - ws[j - 1])

    def energy_below(w):
        j = min(max(int((w - ws[0]) / (ws[1] - ws[0])), 0), m - 1)
        s = (w - ws[j]) / (ws[j + 1] - ws[j])
        return c[j] + s * (c[j + 1] - c[j])

    lo, hi = at(0.002 * c[-1]), at(0.995 * c[-1])
    dw = (hi - lo) / N
    out = []
    for j in range(N):
        a = lo + dw * j
        amp = math.sqrt(2 * (energy_below(a + dw) - energy_below(a)))
        w = a + 0.5 * dw
        k = wave_number(w)
        den = -math.expm1(-2 * k * H)
        out.append((k, w, amp, amp * w / den, amp * w * w / den))
    return sorted(out)


def main():
    comps = components()
    sigma = lambda p: math.sqrt(sum((c[2] * c[1] ** p) ** 2 for c in comps) / 2)
    lim_u, lim_a = CUT_FRACTION * TOL * sigma(1), CUT_FRACTION * TOL * sigma(2)
    print(f"sum of all amplitudes {sum(c[2] for c in comps):.1f} m; the shortest "
          f"component's {comps[-1][2] * 100:.1f} cm; limits u {lim_u:.2e} m/s, a {lim_a:.2e} m/s2")
    print("z (m) | decay prefix | |dzs/deta| | largest E allowed (m) | elevation prefix")
    for z in [-18, -60, -100, -150, -200, -250, -300, -310, -315, -319, -319.9]:
        decay = next((m for m in range(N)
                      if 2 * math.exp(comps[m][0] * z) * sum(c[3] for c in comps[m:]) <= lim_u
                      and 2 * math.exp(comps[m][0] * z) * sum(c[4] for c in comps[m:]) <= lim_a), N)
        kept = comps[:decay]
        su = sum(2 * c[0] * c[3] * math.exp(c[0] * z) for c in kept)
        sa = sum(2 * c[0] * c[4] * math.exp(c[0] * z) for c in kept)
        dzs = (z + H) / H
        allowed = min(lim_u / su, lim_a / sa) / dzs
        # the elevation prefix: the fewest leading components whose tail fits
        elev = next((m for m in range(N + 1) if sum(c[2] for c in comps[m:]) <= allowed), N)
        print(f"{z:7.1f} | {decay:3d} | {dzs:.4f} | {allowed:.2e} | {elev}")


if __name__ == "__main__":
    main()
