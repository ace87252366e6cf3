// shim_system.cpp - SerialSystem (the System of one network on one rank) and the
// factor preconditioner, through the shared library's internal classes, on a rigid
// and an elastic portal frame with a clamped joint (shim_networks.h) and a
// cantilever:
//  - the Tpetra CrsMatrix Hessian (graph of the CSR pattern, built once) applies as
//    the Problem's CSR Hessian and the matrix-free HVP (1e-12 relative), also after a
//    second assembly at another state (values replaced in the same graph);
//  - energy and gradient through Tpetra vectors equal rn_network_energy / _gradient;
//  - DofBlocks: every joint DOF is an interface DOF, rod interiors carry their rod;
//    the terminal-edge DOFs (x_n, theta) of the rod ends at a joint, which the joint's
//    stencil couples across rods (both models), are interface DOFs too: 4 per end;
//    interface points are the joints' positions;
//  - the factor preconditioner inverts H exactly where H is positive definite
//    (|H M^{-1} r - r| <= 1e-10 |r|), is unshifted there, and shifted (SPD, r' M^{-1} r
//    > 0) at an indefinite Hessian (the compressed column of shim_buckling);
//  - save_state / restore_state give back bit-identical energies;
//  - the LOBPCG stability check given tr-krylov's workspace (solve_stability's ws,
//    issue 22) uses the workspace's preconditioner without setting it up again, and
//    finds the same verdict, zero modes and lowest eigenvalue (1e-6) as with a
//    preconditioner of its own.
#include <cmath>
#include <cstdio>
#include <vector>

#include <Tpetra_Core.hpp>

#include "pc/impls/factor/factor_preconditioner.hpp"
#include "krylov/minres.hpp"
#include "pc/preconditioner.hpp"
#include "newton/solvers.hpp"
#include "eigen/stability.hpp"
#include "system/system_serial.hpp"

#include "rodnet.h"
extern "C" {
#include "testutil.h"
}

extern "C" rn_network *shim_system_portal(rn_context *ctx, int elastic);
extern "C" rn_network *shim_system_column(rn_context *ctx);

using namespace rodnet;

static double rel(const TMV &a, const TMV &b) {
  TMV d(a, Teuchos::Copy);
  d.update(-1.0, b, 1.0);
  return d.getVector(0)->norm2() / std::max(b.getVector(0)->norm2(), 1e-300);
}

static void perturb(TMV &x, double a) {
  double *p = host_data(x);
  for (size_t i = 0; i < x.getLocalLength(); ++i)
    p[i] += a * std::sin(0.3 * static_cast<double>(i) + 0.2);
}

// coupled: rod DOFs in the interface (rn_network_dof_blocks).
static void check_network(rn_network *net, const char *label, size_t expect_coupled) {
  Problem p(net);
  SerialSystem sys(p);
  const size_t n = p.size();
  TMV x(sys.map(), 1), v(sys.map(), 1), y(sys.map(), 1), z(sys.map(), 1), g(sys.map(), 1);
  sys.get_state(x);
  perturb(x, 1e-3);
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) perturb(x, 2e-3);
    sys.assemble_hessian(x);
    perturb(v, 1.0);
    sys.hessian()->apply(v, y);
    p.hessian_apply(host_data(v), host_data(z));
    const double d_csr = rel(y, z);
    p.hvp(host_data(x), host_data(v), host_data(z));
    const double d_hvp = rel(y, z);
    printf("%s, assembly %d: CrsMatrix vs CSR %.2e, vs matrix-free HVP %.2e\n", label,
           pass + 1, d_csr, d_hvp);
    CHECK(d_csr <= 1e-14 && d_hvp <= 1e-12);
  }
  double E1 = 0.0, E2 = 0.0;
  std::vector<double> gref(n);
  CHECK(sys.gradient(x, &E1, g) == RN_OK);
  CHECK_STATUS(rn_network_gradient(net, host_data(x), &E2, gref.data()), RN_OK);
  CHECK(E1 == E2);
  for (size_t i = 0; i < n; ++i) CHECK(host_data(g)[i] == gref[i]);
  // blocks
  const DofBlocks &b = sys.blocks();
  std::vector<rn_dof_info> info(n);
  CHECK_STATUS(rn_network_dof_info(net, info.data()), RN_OK);
  size_t joint_dofs = 0, coupled = 0;
  for (size_t i = 0; i < n; ++i) {
    if (info[i].joint >= 0) {
      ++joint_dofs;
      CHECK(b.block[i] == -1);
    }
    if (info[i].rod >= 0 && b.block[i] >= 0) CHECK(b.block[i] == info[i].rod);
    if (info[i].rod >= 0 && b.block[i] == -1) ++coupled;
  }
  CHECK(b.num_rods == rn_network_num_rods(net));
  CHECK(b.interface.size() == joint_dofs + coupled);
  printf("%s: %zu DOFs, %zu joint DOFs, %zu rod DOFs coupled across rods\n", label, n,
         joint_dofs, coupled);
  CHECK(coupled == expect_coupled);
  for (const DofBlocks::Interface &f : b.interface) {
    const rn_dof_info &d = info[static_cast<size_t>(f.local)];
    if (d.joint < 0) continue;
    double pj[3];
    CHECK_STATUS(rn_network_joint_position(net, d.joint, pj), RN_OK);
    CHECK(f.point[0] == pj[0] && f.point[1] == pj[1] && f.point[2] == pj[2]);
    CHECK(f.kind == (d.kind == RN_DOF_POSITION ? d.component : 3 + d.component));
  }
  // save / restore
  double Ea = 0.0;
  TMV x0(sys.map(), 1);
  sys.get_state(x0);
  CHECK(sys.save_state());
  CHECK(sys.energy(x, &Ea) == RN_OK);
  TMV xe(x, Teuchos::Copy); /* accept() resets rigid-joint rotations in x */
  sys.accept(x);
  sys.restore_state();
  TMV x1(sys.map(), 1);
  sys.get_state(x1);
  CHECK(rel(x1, x0) == 0.0);
  double Ec = 0.0;
  CHECK(sys.energy(xe, &Ec) == RN_OK && Ec == Ea);
  sys.accept(x0);
  sys.restore_state();
  TMV x2(sys.map(), 1);
  sys.get_state(x2);
  CHECK(rel(x2, x0) == 0.0);
}

static void check_factor(rn_network *net, const char *label, bool definite) {
  Problem p(net);
  SerialSystem sys(p);
  TMV x(sys.map(), 1), r(sys.map(), 1), y(sys.map(), 1), z(sys.map(), 1);
  sys.get_state(x);
  sys.assemble_hessian(x);
  FactorPreconditioner prec(RN_FACTOR_AUTO);
  prec.setup(sys);
  perturb(r, 1.0);
  prec.inverse()->apply(r, y);
  sys.hessian()->apply(y, z);
  Teuchos::Array<double> ry(1);
  r.dot(y, ry());
  printf("%s: shift %.3e, |H M^-1 r - r| / |r| = %.3e, r' M^-1 r = %.3e\n", label,
         prec.shift(), rel(z, r), ry[0]);
  CHECK(prec.name() == "factor" && prec.stats().setups == 1 && prec.stats().applies == 1);
  CHECK(ry[0] > 0.0);
  if (definite)
    CHECK(!prec.stats().shifted && prec.shift() == 0.0 && rel(z, r) <= 1e-10);
  else
    CHECK(prec.stats().shifted && prec.shift() > 0.0);
}

static void check_stability_reuse(rn_network *net, const char *label) {
  Problem p(net);
  rn_solve_options opt;
  rn_solve_options_default(&opt);
  opt.solver = RN_SOLVER_TR_KRYLOV;
  opt.preconditioner = RN_PRECOND_DD;
  opt.stability_method = RN_STABILITY_LOBPCG;
  KrylovWorkspace ws(p, nullptr, opt);
  System &sys = ws.system();
  TMV x(sys.map(), 1);
  sys.get_state(x);
  sys.assemble_hessian(x);
  ws.preconditioner().setup(sys);
  const long setups = ws.preconditioner().stats().setups;
  const rn_stability own = solve_stability(p, nullptr, opt, RN_FACTOR_AUTO);
  const rn_stability reused = solve_stability(p, nullptr, opt, RN_FACTOR_AUTO, &ws);
  printf("%s, LOBPCG: own preconditioner %.9e (%d iterations), the workspace's %.9e "
         "(%d iterations), workspace set-ups %ld -> %ld\n",
         label, own.lowest_eigenvalue, own.iterations, reused.lowest_eigenvalue,
         reused.iterations, setups, ws.preconditioner().stats().setups);
  CHECK(setups == 1 && ws.preconditioner().stats().setups == setups);
  CHECK(ws.preconditioner().stats().applies > 0); // LOBPCG applied it
  CHECK(own.checked && reused.checked && own.method == RN_STABILITY_LOBPCG &&
        reused.method == RN_STABILITY_LOBPCG);
  CHECK(own.verified_minimum == reused.verified_minimum &&
        own.zero_modes == reused.zero_modes);
  CHECK(std::fabs(own.lowest_eigenvalue - reused.lowest_eigenvalue) <=
        1e-6 * std::fabs(own.lowest_eigenvalue) + 1e-12 * own.scale);
}

int main(int argc, char **argv) {
  Tpetra::ScopeGuard guard(&argc, &argv);
  rn_context *ctx = NULL;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  {
    rn_network *net = shim_system_portal(ctx, 0);
    check_network(net, "rigid portal", 0); /* rigid joints: the ends stay rod-interior */
    check_factor(net, "rigid portal, factor", true);
    check_stability_reuse(net, "rigid portal");
    rn_network_destroy(&net);
    net = shim_system_portal(ctx, 1);
    check_network(net, "elastic portal", 16); /* x_n, theta of 2 ends at A and at B */
    rn_network_destroy(&net);
    net = shim_system_column(ctx); /* compressed straight column: H indefinite */
    check_factor(net, "compressed column, factor", false);
    rn_network_destroy(&net);
  }
  rn_context_destroy(&ctx);
  return rn_test_finish("shim_system");
}
