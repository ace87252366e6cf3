#!/usr/bin/env python3
"""check_post_buckling.py RESULT.json PNG: `rodnet homogenize --post-buckling` on the
honeycomb under equibiaxial compression (in-plane modes): past the critical strain
the bifurcated branch of the 2 x 2 supercell carries less compressive stress and
has a lower energy than the principal (cell-periodic) branch, is a verified minimum
(rn_network_stability) where the principal state is not, and its pattern has the
period of the critical wave vector (M points: no cell-periodic share).  The
principal branch is the regular honeycomb's under equibiaxial compression: the
struts only shorten, the stress is linear in the strain (secant modulus constant
to 1 %, the geometric nonlinearity being of the order of the strain); a principal
relaxation that falls onto the bifurcated branch (as it did from the critical
state itself, where K_uu is singular) fails here."""
import json
import sys


def main():
    r = json.load(open(sys.argv[1]))
    inst = r["instability"]
    assert inst["kind"] == "local", inst
    xi = inst["wave_vector"]
    assert all(abs(abs(x) - 0.5) < 1e-3 or abs(x) < 1e-3 for x in xi), xi
    pb = r["post_buckling"]
    assert pb["supercell"] == [2, 2], pb["supercell"]
    assert pb["out_of_plane_pinned"] is True
    steps = pb["steps"]
    assert len(steps) >= 3, len(steps)
    ec = inst["strain"][0]
    for s in steps:
        assert s["converged"] and s["verified_minimum"], s
        assert s["principal_verified_minimum"] is False, s
        assert s["principal_lowest_eigenvalue"] < 0 < s["lowest_eigenvalue"], s
        assert s["energy_per_cell"] < s["principal_energy_per_cell"], s
        # equibiaxial compression: both normal stresses negative, the bifurcated
        # ones smaller in magnitude than the principal ones
        for v in (0, 1):
            assert s["principal_stress"][v] < s["stress"][v] < 0, s
        assert s["strain"][0] < ec, (s["strain"], ec)
    secant = [s["principal_stress"][0] / s["strain"][0] for s in steps]
    assert all(abs(m - secant[0]) <= 1e-2 * abs(secant[0]) for m in secant), secant
    # the stress stays below the principal branch by a growing margin
    gaps = [s["stress"][0] - s["principal_stress"][0] for s in steps]
    assert all(b > a for a, b in zip(gaps, gaps[1:])), gaps
    amps = [s["amplitude"] for s in steps]
    assert all(b > a for a, b in zip(amps, amps[1:])), amps
    # periodicity: the displacement from the principal state lives on the
    # supercell's non-zero harmonics (the M points of the cell)
    share0 = [h["share"] for h in pb["harmonics"] if h["wave_vector"] == [0, 0]]
    assert len(pb["harmonics"]) == 4 and share0[0] < 1e-4, pb["harmonics"]
    assert pb["pattern_written"] and pb["png"]
    with open(sys.argv[2], "rb") as f:
        assert f.read(8) == b"\x89PNG\r\n\x1a\n"
    print("post-buckling: %d steps, stress %.4g vs principal %.4g at the end, share "
          "at xi = 0: %.2g" % (len(steps), steps[-1]["stress"][0],
                                steps[-1]["principal_stress"][0], share0[0]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
