# check_spectral_ode.py - an independent check of src/kernels/eigen_spectral.c (docs/theory.md
# §8.10): the plane-strain half-space with a layer [z1, z2] of eigenstrain varying as e^{i q x}
# (q = 1, 2G = 1), solved region by region (above, inside, below the layer): the homogeneous
# solutions (A + B z) e^{-z}, (C + D z) e^{z} of the Navier equations, the particular solution of
# a constant eigenstress, continuity of u and of the traction sigma_zj at the faces, a free
# surface and decay. Prints sigma_xx, sigma_yy, sigma_zz, sigma_xz per 2G at three depths for the
# columns xx, yy, zz, xz; compare with mc_spec_point_stress(k, 1, 0, z, 0.4, 1.1) (m units, q = 1).
# Run: python3 tools/check_spectral_ode.py   (needs sympy)
import sympy as sp

nu = sp.Rational(3, 10)
G = sp.Rational(1, 2)
lam = 2 * G * nu / (1 - 2 * nu)
z = sp.symbols('z')


def fields(c, tau):
    """u = homogeneous + particular; the stresses (xx, yy, zz, xz)"""
    ux = (c[0] + c[1] * z) * sp.exp(-z) + (c[2] + c[3] * z) * sp.exp(z)
    uz = (c[4] + c[5] * z) * sp.exp(-z) + (c[6] + c[7] * z) * sp.exp(z)
    txx, tyy, tzz, txz = tau
    ux += txx / ((lam + 2 * G) * sp.I)  # constant eigenstress: i sigma_xx = 0, i sigma_xz = 0
    uz += txz / (G * sp.I)
    exx, ezz = sp.I * ux, sp.diff(uz, z)
    exz = (sp.diff(ux, z) + sp.I * uz) / 2
    tr = exx + ezz
    return ux, uz, lam * tr + 2 * G * exx - txx, lam * tr - tyy, lam * tr + 2 * G * ezz - tzz, \
        2 * G * exz - txz


def navier(f):
    """the coefficients of e^{-z}, z e^{-z}, e^{z}, z e^{z} in both equilibrium equations"""
    out = []
    for r in (sp.I * f[2] + sp.diff(f[5], z), sp.I * f[5] + sp.diff(f[4], z)):
        r = sp.expand(r)
        for e in (sp.exp(-z), sp.exp(z)):
            q = sp.expand(r.coeff(e))
            out += [q.coeff(z, 0), q.coeff(z, 1)]
    return out


def solve(comp, z1, z2, zo):
    e = {0: (1, 0, 0, 0), 1: (0, 1, 0, 0), 2: (0, 0, 1, 0), 5: (0, 0, 0, 1)}[comp]
    tr = e[0] + e[1] + e[2]
    tau = (lam * tr + 2 * G * e[0], lam * tr + 2 * G * e[1], lam * tr + 2 * G * e[2], 2 * G * e[3])
    c0, c1, c2 = sp.symbols('a0:8'), sp.symbols('b0:8'), list(sp.symbols('c0:8'))
    for k in (2, 3, 6, 7):  # below the layer: decaying only
        c2[k] = 0
    R0, R1, R2 = fields(c0, (0, 0, 0, 0)), fields(c1, tau), fields(c2, (0, 0, 0, 0))
    eqs = [R0[4].subs(z, 0), R0[5].subs(z, 0)]
    for a, b, zz in ((R0, R1, z1), (R1, R2, z2)):
        eqs += [sp.expand(a[i].subs(z, zz) - b[i].subs(z, zz)) for i in (0, 1, 4, 5)]
    for R in (R0, R1, R2):
        eqs += navier(R)
    unknowns = list(c0) + list(c1) + [c2[0], c2[1], c2[4], c2[5]]
    sol = sp.solve([q for q in eqs if q != 0], unknowns, dict=True)[0]
    R = R0 if zo < z1 else (R1 if zo < z2 else R2)
    return [complex(sp.N(f.subs(sol).subs({u: 0 for u in unknowns}).subs(z, zo), 15))
            for f in R[2:]]


if __name__ == '__main__':
    z1, z2 = sp.Rational(2, 5), sp.Rational(11, 10)
    for comp in (0, 1, 2, 5):
        for zo in (sp.Rational(1, 5), sp.Rational(3, 4), sp.Rational(8, 5)):
            print(comp, float(zo), ["%.15f%+.15fj" % (v.real, v.imag) for v in solve(comp, z1, z2, zo)])
