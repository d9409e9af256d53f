"""The discretised EHL problem: scikit-fem Reynolds forms with SUPG, FFT elastic deflection, load balance.

Part of :mod:`lubedyn.lubrication.ehl` (the package docstring gives the equations and sources)."""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import scipy.sparse as sp
from skfem import BilinearForm, LinearForm, asm
from skfem.helpers import dot, grad

from .. import mesh as meshes
from ..elastic import ElasticKernel, line_influence_matrix
from ..errors import InputError
from ..laws import contact as hertz
from ..reynolds.forms import (advection_form, diffusion_form, flux_load_form, make_basis, mass_form, source_load_form,
                              streamline_form)
from .assembly import ElementForms, UniformForms
from .contact import EHLContact, _eyring_terms, _log_slope, supg_parameter
from .options import EHLGrid, EHLOptions

# ---------------------------------------------------------------- SUPG forms
@LinearForm
def _supg_load(v, w):
    return w["t"] * dot(w["u"], grad(v))


@BilinearForm
def _supg_derivative(u, v, w):
    """tau (u_m . grad v) (e . grad u): SUPG test against a directional derivative."""
    return w["t"] * dot(w["u"], grad(v)) * dot(w["e"], grad(u))


@BilinearForm
def _directional(u, v, w):
    """k (e . grad u) v."""
    return w["k"] * dot(w["e"], grad(u)) * v


class _Problem:
    def __init__(self, contact: EHLContact, grid: EHLGrid, options: EHLOptions):
        self.c, self.g, self.o = contact, grid, options
        W = contact.hertz_load()
        if contact.is_line:
            hz = hertz.line_contact(W, contact.radius_x, contact.e_star)
            self.bx, self.by, self.ph = hz.b, None, hz.p0
            self.delta_hertz = None
        else:
            hp = hertz.point_contact(W, contact.radius_x, contact.radius_y, contact.e_star)
            # hp.a lies along the larger radius
            if contact.radius_y >= contact.radius_x:
                self.bx, self.by = hp.b, hp.a
            else:
                self.bx, self.by = hp.a, hp.b
            self.ph = hp.p0
            self.delta_hertz = hp.approach
        self.hscale = self.bx**2 / contact.radius_x
        nx = grid.nx
        self.graded = bool(grid.graded)
        if self.graded and not contact.is_line:
            raise InputError(f"grid refine = {grid.refine!r}: graded grids are for line contacts")
        xs = grid.x_nodes() * self.bx if self.graded else np.linspace(grid.x_min * self.bx, grid.x_max * self.bx, nx)
        # SUPG element size: the spacing, per element ((E, 1), broadcast over the quadrature points) on a
        # graded grid
        self.dx = np.diff(xs)[:, None] if self.graded else xs[1] - xs[0]
        if contact.is_line:
            self.shape = (nx,)
            spacing = (self.dx,)
        else:
            ny = grid.ny or int(round((nx - 1) * 2 * grid.y_max * self.by / ((grid.x_max - grid.x_min) * self.bx))) + 1
            ny += (ny + 1) % 2  # odd: a node row on the centre line
            ys = np.linspace(-grid.y_max * self.by, grid.y_max * self.by, ny)
            self.dy = ys[1] - ys[0]
            self.shape = (nx, ny)
            spacing = (self.dx, self.dy)
        self.xs = xs
        self.ys = None if contact.is_line else ys
        # Mesh and P1 basis are built on first use (:attr:`mesh`, :attr:`basis`): the multigrid method
        # needs neither (at 257 x 257 mesh, basis and boundary dofs together cost about a quarter of a
        # whole multigrid solve).
        # The dofs of P1 on scikit-fem's tensor meshes are the vertices, numbered x-major (vertex
        # ix * ny + iy sits at (xs[ix], ys[iy]); MeshLine: in the order of xs): so the dof locations,
        # the grid index of every dof (identity) and the boundary dofs follow from xs, ys alone
        # (tests/test_ehl_multigrid.py checks them against the basis's).
        self._mesh = None
        self._basis = None
        if contact.is_line:
            self.doflocs = xs[None, :].copy()
            boundary = np.zeros(self.shape, dtype=bool)
            boundary[[0, -1]] = True
        else:
            self.doflocs = np.stack([np.repeat(xs, ny), np.tile(ys, nx)])
            boundary = np.zeros(self.shape, dtype=bool)
            boundary[[0, -1], :] = True
            boundary[:, [0, -1]] = True
        self.N = int(np.prod(self.shape))
        self.flat = np.arange(self.N)
        loc = self.doflocs
        # elastic operator: FFT of the Toeplitz kernel (uniform grids), the dense matrix of the node cells
        # (graded line grids, :func:`lubedyn.lubrication.elastic.line_influence_matrix`)
        self.kernel = None if self.graded else ElasticKernel(self.shape, spacing, contact.e_star)
        x = loc[0]
        self.rigid = x**2 / (2 * contact.radius_x)
        if not contact.is_line:
            self.rigid = self.rigid + loc[1] ** 2 / (2 * contact.radius_y)
        # assembly templates and nodal weights int phi_i dA, built on first use
        # (seconds at 513 x 513, which the multigrid method does not need)
        self._forms = None
        self._weights = None
        self._u = None
        # Dirichlet p = 0 on the whole boundary
        self.fixed = boundary.ravel()
        self.free0 = ~self.fixed
        self._Kdense = line_influence_matrix(xs, contact.e_star) if self.graded else None
        self._Kloc = None

    @property
    def mesh(self):
        """The film mesh (:func:`lubedyn.lubrication.mesh.rectangle` quads or an interval), built on first use."""
        if self._mesh is None:
            if self.c.is_line:
                self._mesh = meshes.interval(self.xs[0], self.xs[-1], self.shape[0] - 1,
                                             points=self.xs if self.graded else None)
            else:
                self._mesh = meshes.rectangle(self.xs, self.ys, "quad")
        return self._mesh

    @property
    def basis(self):
        """P1 basis on :attr:`mesh` (dof i at ``doflocs[:, i]``), built on first use."""
        if self._basis is None:
            self._basis = make_basis(self.mesh, "P1")
        return self._basis

    @property
    def u(self):
        """Entrainment velocity at the quadrature points (the FEM forms' advection field)."""
        if self._u is None:
            b = self.basis
            u = np.zeros((1 if self.c.is_line else 2, b.nelems, b.X.shape[-1]))
            u[0] = self.c.mean_speed
            self._u = u
        return self._u

    @property
    def forms(self):
        if self._forms is None:
            self._forms = ElementForms(self.basis) if self.graded else UniformForms(self.basis)
        return self._forms

    @property
    def weights(self):
        """int phi_i dA [m^2 or m] of every dof (P1 on the uniform grid)."""
        if self._weights is None:
            b = self.basis
            self._weights = self.forms.vector([(np.ones((b.nelems, b.X.shape[-1])), self.forms.val)])
        return self._weights

    def uniform_weights(self):
        """The same weights without the assembly templates: dx dy (or dx) times the
        number of cells at the node over the number of a cell's vertices (P1 on
        a uniform tensor grid; equal to :attr:`weights` to round-off)."""
        if self._weights is None:
            if self.graded:
                cells = np.diff(self.xs)
                w = np.concatenate([[0.0], cells]) * 0.5 + np.concatenate([cells, [0.0]]) * 0.5
            elif self.c.is_line:
                w = np.full(self.shape, self.dx)
                w[[0, -1]] *= 0.5
            else:
                w = np.full(self.shape, self.dx * self.dy)
                w[[0, -1], :] *= 0.5
                w[:, [0, -1]] *= 0.5
            self._weights = w.ravel()[self.flat]
        return self._weights

    # -- elastic operator in dof ordering --------------------------------
    def deflect(self, p):
        if self.graded:  # line dofs are the nodes in order (flat is the identity)
            return self._Kdense @ p
        grid = np.zeros(np.prod(self.shape))
        grid[self.flat] = p
        u = self.kernel.deflect(grid.reshape(self.shape)).ravel()
        return u[self.flat]

    def K_dense(self):
        if self._Kdense is None:
            Kk = self.kernel._kernel
            if self.c.is_line:
                i = self.flat
                M = Kk[i[:, None] - i[None, :] + self.shape[0] - 1]
            else:
                ny = self.shape[1]
                ix, iy = self.flat // ny, self.flat % ny
                M = Kk[ix[:, None] - ix[None, :] + self.shape[0] - 1, iy[:, None] - iy[None, :] + ny - 1]
            self._Kdense = M
        return self._Kdense

    def K_local(self):
        """Sparse truncation of K to offsets |di|, |dj| <= stencil."""
        if self._Kloc is None and self.graded:
            s = self.o.stencil
            n = self.N
            self._Kloc = sp.diags([np.diagonal(self._Kdense, d) for d in range(-s, s + 1)], list(range(-s, s + 1)),
                                  shape=(n, n), format="csr")
        if self._Kloc is None:
            s = self.o.stencil
            Kk = self.kernel._kernel
            rows, cols, vals = [], [], []
            if self.c.is_line:
                n = self.shape[0]
                inv = np.empty(n, dtype=int)
                inv[self.flat] = np.arange(self.N)
                for d in range(-s, s + 1):
                    i = np.arange(max(0, -d), min(n, n - d))
                    rows.append(inv[i]); cols.append(inv[i + d]); vals.append(np.full(i.size, Kk[d + n - 1]))
            else:
                nx, ny = self.shape
                inv = np.empty(nx * ny, dtype=int)
                inv[self.flat] = np.arange(self.N)
                I, J = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
                for di in range(-s, s + 1):
                    for dj in range(-s, s + 1):
                        ok = (I + di >= 0) & (I + di < nx) & (J + dj >= 0) & (J + dj < ny)
                        a = (I[ok] * ny + J[ok])
                        bb = ((I[ok] + di) * ny + J[ok] + dj)
                        rows.append(inv[a]); cols.append(inv[bb])
                        vals.append(np.full(a.size, Kk[di + nx - 1, dj + ny - 1]))
            self._Kloc = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(self.N, self.N))
        return self._Kloc

    # -- residual and Jacobian blocks ------------------------------------
    def film(self, p, h00):
        return h00 + self.rigid + self.deflect(p)

    def _coefficients(self, pq, hq, grad_p):
        """Pointwise coefficients at the quadrature points, shared by both assemblies: eta, eta',
        rho, rho', kN = rho h^3/(12 eta), the Eyring or Herschel-Bulkley factors ``ey`` (:func:`_eyring_terms`,
        None if Newtonian), k = kN Phi, and the SUPG parameter (Pe = 6 u_m l eta/(h^2 Phi), rho cancels;
        tau, tau'(Pe))."""
        lub = self.c.lubricant
        with np.errstate(over="ignore", invalid="ignore"):
            eta, deta = lub.viscosity(pq), lub.viscosity.derivative(pq)
            rho, drho = lub.density(pq), lub.density.derivative(pq)
        kN = rho * hq**3 / (12 * eta)
        ey = _eyring_terms(lub, hq, grad_p, eta)
        k = kN if ey is None else kN * ey["phi"]
        Pe, tau, dtau_dPe = supg_parameter(self.c.mean_speed, self.dx, rho, hq, k)
        return SimpleNamespace(eta=eta, deta=deta, rho=rho, drho=drho, kN=kN, ey=ey, k=k, Pe=Pe, tau=tau,
                               dtau_dPe=dtau_dPe)

    def _coefficient_derivatives(self, cf, pq, hq):
        """dk/dp, dk/dh, dtau/dp, dtau/dh at fixed grad p (the grad p terms of Eyring flow are
        assembled by the callers), and rho'' (None for a pressure-independent density).

        d tau/dp = tau'(Pe) Pe eta'/eta, d tau/dh = -tau'(Pe) Pe (2/h + Phi_h/Phi); with Eyring flow
        k = kN Phi(x), x = h |grad p|/(2 tau0), so dk/dh gains kN Phi' x/h; with Herschel-Bulkley flow
        Phi also depends on eta (consistency): dk/dp gains kN Phi (1 - 1/n) eta'/eta and d tau/dp is
        tau'(Pe) Pe (1/n) eta'/eta (Pe ~ eta/Phi ~ eta^(1/n)).  rho'' by a central
        difference on the smooth branch p > 0 (rho' jumps at p = 0, where rho = rho(max(p, 0)) has
        rho'' = 0 on the flat side)."""
        eta, rho, drho, kN, ey, Pe, dtau_dPe = cf.eta, cf.rho, cf.drho, cf.kN, cf.ey, cf.Pe, cf.dtau_dPe
        dlog_eta = _log_slope(eta, cf.deta)
        dk_dp = hq**3 / 12 * (drho - rho * dlog_eta) / eta
        dk_dh = rho * 3 * hq**2 / (12 * eta)
        dtau_dp = dtau_dPe * Pe * dlog_eta
        dtau_dh = -2.0 * dtau_dPe * Pe / hq
        if ey is not None:
            # k = kN Phi; Herschel-Bulkley: Phi depends on eta too (d ln Phi/d ln eta = 1 - 1/n),
            # so Pe ~ eta/Phi has d ln Pe/dp = (1 - d ln Phi/d ln eta) eta'/eta
            dk_dp = dk_dp * ey["phi"] + kN * ey["phi"] * ey["dlnphi_dlneta"] * dlog_eta
            dk_dh = dk_dh * ey["phi"] + kN * ey["dphi_dh"]
            dtau_dp = dtau_dp - dtau_dPe * Pe * ey["dlnphi_dlneta"] * dlog_eta
            dtau_dh = dtau_dh - dtau_dPe * Pe * ey["dlnphi_dh"]
        d2rho = None
        if np.any(drho != 0.0):
            density = self.c.lubricant.density
            dp_ = 1e-6 * self.ph
            lo, hi = np.maximum(pq - dp_, 0.5 * pq), pq + dp_
            with np.errstate(invalid="ignore", divide="ignore"):
                d2rho = np.where(pq > 0, (density.derivative(hi) - density.derivative(lo)) / (hi - lo), 0.0)
        return dk_dp, dk_dh, dtau_dp, dtau_dh, d2rho

    def assemble(self, p, h00, jac=True):
        """Residual R(p, h00) of the stabilised Reynolds equation and, with
        ``jac``, its exact derivatives A = dR/dp at fixed film and D = dR/dh
        (nodal film), vectorised on the uniform grid (:mod:`lubedyn.lubrication.ehl.assembly`;
        :meth:`assemble_skfem` is the same with scikit-fem forms, for checks)."""
        c, F = self.c, self.forms
        hn = self.film(p, h00)
        hfloor = self.o.h_floor * self.hscale
        hn_eff = np.maximum(hn, hfloor)
        pv, pg = F.interpolate(p)
        hq, hg = F.interpolate(hn_eff)
        pq = np.maximum(pv, 0.0)
        cf = self._coefficients(pq, hq, pg)
        rho, drho, kN, ey, k, Pe, tau, dtau_dPe = cf.rho, cf.drho, cf.kN, cf.ey, cf.k, cf.Pe, cf.tau, cf.dtau_dPe
        um = c.mean_speed
        hdot = c.squeeze_velocity
        dim = F.dim
        strong = um * (rho * hg[0] + hq * drho * pg[0]) + rho * hdot
        if self.o.consistent_supg:
            # recovered Poiseuille flux F = -k grad p at the nodes (lumped L2
            # projection); its divergence completes the strong residual, so the
            # SUPG term is consistent and the scheme second order
            for d in range(dim):
                Fd = -F.vector([(k * pg[d], F.val)]) / self.weights
                strong = strong + F.interpolate(Fd)[1][d]
        # R_i = int (k grad p - rho h u_m + tau strong u_m) . grad v_i + rho hdot v_i
        terms = [(k * pg[d], F.grd[d]) for d in range(dim)]
        terms[0] = (k * pg[0] - rho * hq * um + tau * strong * um, F.grd[0])
        if hdot != 0.0:
            terms.append((rho * hdot, F.val))
        R = F.vector(terms)
        if not jac:
            return R, hn
        dk_dp, dk_dh, dtau_dp, dtau_dh, d2rho = self._coefficient_derivatives(cf, pq, hq)
        # d(strong)/dp_j without the film dependence (that is in D):
        # u_m (rho' h_x + h rho'' p_x) phi_j + u_m rho' h d_x phi_j + rho' hdot phi_j
        if d2rho is not None:
            d_strong_dp = um * (drho * hg[0] + hq * d2rho * pg[0]) + drho * hdot
        else:
            d_strong_dp = 0.0
        # A: diffusion k, advection (k' grad p - rho' h u) phi_j . grad v, the
        # squeeze mass rho' hdot, SUPG: tau (d strong/dp) u.grad v + tau' strong u.grad v
        Aterms = [(k, F.gg[d][d]) for d in range(dim)]
        Aterms += [(dk_dp * pg[d], F.adv[d]) for d in range(dim)]
        if ey is not None:
            c2 = kN * ey["c2"]
            Aterms += [(c2 * pg[d] * pg[e], F.gg[d][e]) for d in range(dim) for e in range(dim)]
            # tau(Pe(grad p)): d tau/d(d_e p) = -tau'(Pe) Pe c2/k d_e p, times strong u_m . grad v
            Aterms += [(-dtau_dPe * Pe * ey["c2_rel"] * pg[e] * strong * um, F.gg[0][e]) for e in range(dim)]
        Aterms.append((-drho * hq * um + (tau * d_strong_dp + dtau_dp * strong) * um, F.adv[0]))
        Aterms.append((tau * drho * hq * um * um, F.gg[0][0]))
        if hdot != 0.0:
            Aterms.append((drho * hdot, F.mass))
        Dterms = [(dk_dh * pg[d], F.adv[d]) for d in range(dim)]
        Dterms.append((-rho * um + (tau * um * drho * pg[0] + dtau_dh * strong) * um, F.adv[0]))
        Dterms.append((tau * rho * um * um, F.gg[0][0]))
        A = F.matrix(Aterms)
        D = F.matrix(Dterms)
        if self.o.consistent_supg:
            Ml_inv = sp.diags(1.0 / self.weights)
            for d in range(dim):
                S = F.matrix([(tau * um, F.gg[0][d])])
                gp_terms = [(k, F.dirn[d]), (dk_dp * pg[d], F.mass)]
                if ey is not None:
                    gp_terms += [(c2 * pg[d] * pg[e], F.dirn[e]) for e in range(dim)]
                Gp = F.matrix(gp_terms)
                Gh = F.matrix([(dk_dh * pg[d], F.mass)])
                SM = S @ Ml_inv
                A = A - SM @ Gp
                D = D - SM @ Gh
            A, D = A.tocsr(), D.tocsr()
        # nodes whose film sits on the floor do not feel h changes
        D = D @ sp.diags((hn > hfloor).astype(float))
        return R, hn, A, D, dict(tau=tau, rho=rho)

    def assemble_skfem(self, p, h00, jac=True):
        """Reference assembly with scikit-fem forms (the same equations as :meth:`assemble`)."""
        c, b = self.c, self.basis
        hn = self.film(p, h00)
        hfloor = self.o.h_floor * self.hscale
        hn_eff = np.maximum(hn, hfloor)
        pf, hf = b.interpolate(p), b.interpolate(hn_eff)
        pq, hq = np.maximum(np.asarray(pf), 0.0), np.asarray(hf)
        cf = self._coefficients(pq, hq, np.asarray(pf.grad))
        rho, drho, kN, ey, k, Pe, tau, dtau_dPe = cf.rho, cf.drho, cf.kN, cf.ey, cf.k, cf.Pe, cf.tau, cf.dtau_dPe
        um = c.mean_speed
        u = self.u
        hdot = c.squeeze_velocity
        ugrad_rho_h = um * (rho * hf.grad[0] + hq * drho * pf.grad[0])
        strong = ugrad_rho_h + rho * hdot
        dim = 1 if c.is_line else 2
        if self.o.consistent_supg:
            # recovered Poiseuille flux F = -k grad p at the nodes (lumped L2
            # projection); its divergence completes the strong residual, so the
            # SUPG term is consistent and the scheme second order
            div = 0.0
            for d in range(dim):
                Fd = -np.asarray(asm(source_load_form, b, g=k * pf.grad[d])) / self.weights
                div = div + b.interpolate(Fd).grad[d]
            strong = strong + div
        Kd = asm(diffusion_form, b, a=k)
        R = Kd @ p + asm(flux_load_form, b, f=-rho * hq * u) + asm(source_load_form, b, g=rho * hdot)
        R = R + asm(_supg_load, b, t=tau * strong, u=u)
        if not jac:
            return R, hn
        dk_dp, dk_dh, dtau_dp, dtau_dh, d2rho = self._coefficient_derivatives(cf, pq, hq)
        # d(strong)/dp_j without the h-dependence (in D): u_m (rho' h_x + h rho'' p_x)
        # phi_j + (rho' h u_m) . grad phi_j + rho' hdot phi_j
        if d2rho is not None:
            d_strong_dp = um * (drho * hf.grad[0] + hq * d2rho * pf.grad[0]) + drho * hdot
        else:
            d_strong_dp = 0.0 * hq
        A = (
            Kd
            + asm(advection_form, b, b=dk_dp * pf.grad - drho * hq * u)
            + asm(mass_form, b, c=drho * hdot * np.ones_like(hq))
            + asm(streamline_form, b, s=tau * drho * hq, beta=u)
            + asm(advection_form, b, b=(tau * d_strong_dp + dtau_dp * strong) * u)
        )
        if ey is not None:
            gp = np.asarray(pf.grad)
            c2 = kN * ey["c2"]
            # c2 (grad p . grad phi_j)(grad p . grad v) and d tau/d(grad p) strong (u . grad v)
            A = (A + asm(_supg_derivative, b, t=c2, u=gp, e=gp)
                 + asm(_supg_derivative, b, t=-dtau_dPe * Pe * ey["c2_rel"] * strong, u=u, e=gp))
        A = A.tocsr()
        D = (
            asm(advection_form, b, b=dk_dh * pf.grad - rho * u)
            + asm(streamline_form, b, s=tau * rho, beta=u)
            + asm(advection_form, b, b=(tau * um * drho * pf.grad[0] + dtau_dh * strong) * u)
        ).tocsr()
        if self.o.consistent_supg:
            Ml_inv = sp.diags(1.0 / self.weights)
            for d in range(dim):
                e = np.zeros_like(u)
                e[d] = 1.0
                S = asm(_supg_derivative, b, t=tau, u=u, e=e)
                Gp = asm(_directional, b, k=k, e=e) + asm(mass_form, b, c=dk_dp * pf.grad[d])
                if ey is not None:
                    Gp = Gp + asm(_directional, b, k=c2 * gp[d], e=gp)
                Gh = asm(mass_form, b, c=dk_dh * pf.grad[d])
                A = A - S @ (Ml_inv @ Gp)
                D = D - S @ (Ml_inv @ Gh)
            A, D = A.tocsr(), D.tocsr()
        # nodes whose film sits on the floor do not feel h changes
        D = D @ sp.diags((hn > hfloor).astype(float))
        return R, hn, A, D, dict(tau=tau, rho=rho)
