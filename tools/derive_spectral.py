# derive_spectral.py - re-derives the constants of src/kernels/eigen_spectral.c (docs/theory.md
# §8.10) with sympy: Mura's infinite-space eigenstrain operator in 3-D Fourier space for the mode
# xi = (q, 0, zeta) (q = 1, 2G = 1), its inverse transform in depth by residues at zeta = +-i q
# (K(s) = e^{-|s|} (A + B |s|) per side, plus M_inf inside the layer), the traction of S1 + S2 on
# z = 0, and the half-space (Boussinesq) stress of a unit pressure mode.
# Run: python3 tools/derive_spectral.py   (needs sympy; a minute)
# Derive the lateral-Fourier (k-frame) kernel of a half-space eigenstrain layer.
import sympy as sp
q = sp.Integer(1)   # scaled: t = q z
nu = sp.symbols('nu')
zeta = sp.symbols('zeta')
s = sp.symbols('s', positive=True)
G = sp.Rational(1,2)  # stresses per 2G: set 2G = 1
lam = 2*G*nu/(1-2*nu)
xi = sp.Matrix([q, 0, zeta])
x2 = q**2 + zeta**2
Gh = (sp.eye(3) - xi*xi.T/(2*(1-nu)*x2))/(G*x2)
comps = [(0,0),(1,1),(2,2),(0,1),(1,2),(0,2)]
def unit(c):
    E = sp.zeros(3,3); a,b = comps[c]; E[a,b] = 1; E[b,a] = 1; return E
def C(e):
    return lam*e.trace()*sp.eye(3) + 2*G*e
M = sp.zeros(6,6)
for c in range(6):
    tau = C(unit(c))
    b = -sp.I*(tau*xi)          # b_k = -i xi_l tau_lk (tau symmetric)
    u = Gh*b
    eps = sp.I*(xi*u.T + u*xi.T)/2
    sig = C(eps) - tau
    for r,(a,bb) in enumerate(comps):
        M[r,c] = sp.simplify(sig[a,bb])
Minf = M.applyfunc(lambda f: sp.limit(f, zeta, sp.oo))
R = (M - Minf).applyfunc(sp.simplify)
Kp = R.applyfunc(lambda f: sp.simplify(sp.I*sp.residue(f*sp.exp(sp.I*zeta*s), zeta, sp.I)))
Km = R.applyfunc(lambda f: sp.simplify(-sp.I*sp.residue(f*sp.exp(-sp.I*zeta*s), zeta, -sp.I)))  # K(-s), s>0
print("Minf"); sp.pprint(Minf)
print("K+(s) e^s"); sp.pprint((Kp*sp.exp(s)).applyfunc(sp.expand))
print("K-(-s) e^s"); sp.pprint((Km*sp.exp(s)).applyfunc(sp.expand))

# ---- S2, S3 ----
nu = sp.symbols('nu'); s = sp.symbols('s', positive=True); t = sp.symbols('t', nonnegative=True)
A_p = (Kp*sp.exp(s)).applyfunc(lambda f: sp.simplify(sp.expand(f).coeff(s,0)))
B_p = (Kp*sp.exp(s)).applyfunc(lambda f: sp.simplify(sp.expand(f).coeff(s,1)))
A_m = (Km*sp.exp(s)).applyfunc(lambda f: sp.simplify(sp.expand(f).coeff(s,0)))
B_m = (Km*sp.exp(s)).applyfunc(lambda f: sp.simplify(sp.expand(f).coeff(s,1)))
assert sp.simplify(A_p + B_p*s - Kp*sp.exp(s)) == sp.zeros(6,6)
Rt = sp.diag(1,1,1,1,-1,-1)
# S1+S2 traction at z=0 from a layer [t1,t2]: S1 uses K-(t'), S2 uses K+(t') Rt
t1,t2 = sp.symbols('t1 t2', positive=True)
tp = sp.symbols('tp', positive=True)
S12_0 = (Km.subs(s,tp) + Kp.subs(s,tp)*Rt).applyfunc(lambda f: sp.simplify(sp.integrate(f,(tp,t1,t2))))
print("traction rows zz, yz, xz at z=0:")
sp.pprint(S12_0[2,:]); sp.pprint(S12_0[4,:]); sp.pprint(S12_0[5,:])
# S3: half-space, mode e^{i x}, unit compressive pressure: sigma_zz(0) = -1, shear 0
a,b,c,d = sp.symbols('a b c d')
z = sp.symbols('z')
G = sp.Rational(1,2); lam = 2*G*nu/(1-2*nu)
ux = (a+b*z)*sp.exp(-z); uz = (c+d*z)*sp.exp(-z); uy = 0
# derivatives: d/dx -> i
def grad(u):  # u=(ux,uy,uz) functions of z; returns 3x3 du_i/dx_j
    return sp.Matrix([[sp.I*u[i], 0, sp.diff(u[i], z)] for i in range(3)])
U = [ux, 0, uz]
Gm = grad(U); eps = (Gm + Gm.T)/2
sig = lam*eps.trace()*sp.eye(3) + 2*G*eps
div = [sp.I*sig[0,i] + sp.diff(sig[2,i], z) for i in range(3)]
eqs = [sp.simplify(sp.expand(dv*sp.exp(z))) for dv in div]
eqs_c = []
for e in eqs:
    e = sp.expand(e)
    eqs_c += [e.coeff(z,0), e.coeff(z,1)]
bc = [sp.simplify(sig[2,2].subs(z,0)+1), sp.simplify(sig[0,2].subs(z,0))]
sol = sp.solve([e for e in eqs_c if e != 0] + bc, [a,b,c,d], dict=True)
print(sol)
sol = sol[0]
sig3 = sig.subs(sol)
T = sp.Matrix([sig3[0,0], sig3[1,1], sig3[2,2], sig3[0,1], sig3[1,2], sig3[0,2]]).applyfunc(sp.simplify)
T0 = (T*sp.exp(z)).applyfunc(lambda f: sp.simplify(sp.expand(f).coeff(z,0)))
T1 = (T*sp.exp(z)).applyfunc(lambda f: sp.simplify(sp.expand(f).coeff(z,1)))
print("S3 per unit pressure: T0, T1"); sp.pprint(T0.T); sp.pprint(T1.T)
print("u_z(0) per unit pressure:", sp.simplify(uz.subs(sol).subs(z,0)))
for name,Mx in [('A_p',A_p),('B_p',B_p),('Minf',Minf)]:
    print(name); sp.pprint(Mx)
