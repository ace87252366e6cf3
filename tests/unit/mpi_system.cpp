// mpi_system.cpp - the distributed evaluation layer (shim_cxx/system/dist_system.hpp) on
// any number of ranks against the whole network evaluated on every rank: for a single
// rod, independent rods, a grid with rigid joints, a lattice of one-edge rods with
// both joint models and component pins, and a frame with elastic joints, partitioned
// by rn_partition_rods over the ranks and built as parts from the graph:
//   - the owned DOFs add up to the whole network's and each DOF has one owner;
//   - energy, gradient (owned entries) and Hessian (applied to random vectors) agree
//     with the whole network to round-off at perturbed states, also after reference
//     updates (accept) at accepted states;
//   - the second-order stretching correction of a step sums over the parts to the
//     whole network's;
//   - the Hessian's graph is built once (same object after reassembly);
//   - an error on one rank (a non-finite state there) reaches every rank.
// Run by ctest on 1 and 2 ranks (label mpi) and on 3 ranks (more ranks than rods for
// the single rod and the independent rods).
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include <Tpetra_Core.hpp>

#include "system/dist_system.hpp"
#include "rodnet.h"
#include "rodnet_solve.h"
#include "base/shim_error.hpp"

namespace {

int failures = 0, checks = 0, rank_ = 0;

#define EXPECT(cond, ...)                                                             \
  do {                                                                                \
    ++checks;                                                                         \
    if (!(cond)) {                                                                    \
      ++failures;                                                                     \
      std::fprintf(stderr, "rank %d: %s:%d: %s: ", rank_, __FILE__, __LINE__, #cond); \
      std::fprintf(stderr, __VA_ARGS__);                                              \
      std::fprintf(stderr, "\n");                                                     \
    }                                                                                 \
  } while (0)

using Builder = std::function<void(rn_network *)>;

void props(rn_network *net, int rod) {
  rn_material m;
  rn_section s;
  rn_material_from_E_nu(1e7, 0.3, 500.0, &m);
  rn_section_ellipse(0.012, 0.008, &s);
  rn_network_set_material(net, rod, -1, &m);
  rn_network_set_section(net, rod, -1, &s);
}

int line(rn_network *net, const double a[3], const double b[3], int ne, double bow) {
  std::vector<double> x(3 * static_cast<size_t>(ne + 1));
  for (int i = 0; i <= ne; ++i) {
    const double t = static_cast<double>(i) / ne;
    for (int k = 0; k < 3; ++k) x[3 * i + k] = a[k] + (b[k] - a[k]) * t;
    x[3 * i + 2] += bow * t * (1.0 - t);
  }
  int rod = -1;
  rn_network_add_rod(net, nullptr, ne + 1, x.data(), nullptr, &rod);
  props(net, rod);
  return rod;
}

void single_rod(rn_network *net) {
  const double a[3] = {0, 0, 0}, b[3] = {1, 0.2, 0}, f[3] = {0, 0.3, -0.5},
               m[3] = {0.01, 0.02, 0}, g[3] = {0, 0, -9.81};
  const int r = line(net, a, b, 11, 0.05);
  rn_network_clamp(net, r, RN_START);
  rn_network_add_force(net, r, -1, f);
  rn_network_add_moment(net, r, 5, m);
  rn_network_add_gravity(net, g);
}

void independent(rn_network *net) {
  for (int i = 0; i < 3; ++i) {
    const double a[3] = {0, 1.0 * i, 0}, b[3] = {1, 1.0 * i, 0.1 * i},
                 f[3] = {0.1, 0, -0.2 * i};
    const int r = line(net, a, b, 5 + i, 0.02);
    rn_network_clamp(net, r, RN_START);
    rn_network_add_force(net, r, -1, f);
  }
}

void grid(rn_network *net, int n, int ne, int model) {
  std::vector<int> hor(static_cast<size_t>(n * (n + 1))), ver(hor.size());
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i < n; ++i) {
      const double a[3] = {1.0 * i, 1.0 * j, 0}, b[3] = {i + 1.0, 1.0 * j, 0};
      hor[static_cast<size_t>(j * n + i)] =
          line(net, a, b, ne, 0.03 * ((i + j) % 2 ? 1 : -1));
    }
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j < n; ++j) {
      const double a[3] = {1.0 * i, 1.0 * j, 0}, b[3] = {1.0 * i, j + 1.0, 0};
      ver[static_cast<size_t>(i * n + j)] = line(net, a, b, ne, 0.0);
    }
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      int rods[4], ends[4], v = 0, jt;
      const int mdl =
          model >= 0 ? model : ((i + j) % 2 ? RN_JOINT_ELASTIC : RN_JOINT_RIGID);
      if (i > 0) rods[v] = hor[static_cast<size_t>(j * n + i - 1)], ends[v++] = RN_END;
      if (i < n) rods[v] = hor[static_cast<size_t>(j * n + i)], ends[v++] = RN_START;
      if (j > 0) rods[v] = ver[static_cast<size_t>(i * n + j - 1)], ends[v++] = RN_END;
      if (j < n) rods[v] = ver[static_cast<size_t>(i * n + j)], ends[v++] = RN_START;
      rn_network_add_joint(net, nullptr, static_cast<rn_joint_model>(mdl), v, rods, ends,
                           &jt);
    }
  const int nj = (n + 1) * (n + 1);
  const double f[3] = {0.02, 0.01, 0.3}, m[3] = {0.001, -0.002, 0.003},
               d[3] = {0, 0, 0.01};
  rn_network_pin_joint(net, 0);
  rn_network_pin_joint(net, n);
  rn_network_pin_joint_components(net, nj - 1, RN_FIX_Z);
  rn_network_displace_joint(net, nj - 1, d, nullptr);
  rn_network_add_joint_force(net, nj / 2, f);
  rn_network_add_joint_moment(net, n + 2, m);
}

void elastic_frame(rn_network *net) {
  const double p0[3] = {0, 0, 0}, p1[3] = {0, 0, 1}, p2[3] = {1, 0, 1}, p3[3] = {1, 0, 0},
               p4[3] = {1.5, 0.3, 1.4};
  const double rot[3] = {0, 0.05, 0.02}, f[3] = {0.1, 0.05, -0.2};
  const int c0 = line(net, p0, p1, 4, 0.02), bm = line(net, p1, p2, 6, 0.05);
  const int c1 = line(net, p3, p2, 4, -0.02), br = line(net, p2, p4, 3, 0.0);
  int ra[2] = {c0, bm}, ea[2] = {RN_END, RN_START}, rb[3] = {bm, c1, br},
      eb[3] = {RN_END, RN_END, RN_START}, rc[1] = {c1}, ec[1] = {RN_START}, j;
  rn_network_add_joint(net, "A", RN_JOINT_ELASTIC, 2, ra, ea, &j);
  rn_network_add_joint(net, "B", RN_JOINT_ELASTIC, 3, rb, eb, &j);
  rn_network_add_joint(net, "C", RN_JOINT_ELASTIC, 1, rc, ec, &j);
  rn_network_clamp_joint(net, j);
  rn_network_displace_joint(net, j, nullptr, rot);
  rn_network_clamp(net, c0, RN_START);
  rn_network_add_force(net, br, -1, f);
}

rn_network *build(rn_context *ctx, const Builder &b, int nparts, int part,
                  const std::vector<int> *rp, int nr, const int *nv, int nj,
                  const int *jp, const int *jr) {
  rn_network *net = nullptr;
  rn_network_create(ctx, &net);
  if (rp) rn_network_set_part(net, nparts, part, nr, nv, rp->data(), nj, jp, jr);
  b(net);
  const rn_status st = rn_network_finalize(net);
  EXPECT(st == RN_OK, "finalize: %s", rn_context_last_error(ctx));
  return net;
}

double rnd(uint64_t &s) {
  s = s * 6364136223846793005ULL + 1442695040888963407ULL;
  return static_cast<double>(s >> 11) / 9007199254740992.0 * 2.0 - 1.0;
}

double max_all(double v) {
  double out = v;
  MPI_Allreduce(&v, &out, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return out;
}

long sum_all(long v) {
  long out = v;
  MPI_Allreduce(&v, &out, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  return out;
}

// Results of two whole networks of the same scene: equal (same state, frames).
void compare_results(rn_network *a, rn_network *b, const char *label) {
  double ea[RN_TERM_COUNT], eb[RN_TERM_COUNT];
  const size_t n = rn_network_num_dofs(a);
  std::vector<double> xa(n), xb(n);
  rn_network_get_dofs(a, xa.data());
  rn_network_get_dofs(b, xb.data());
  EXPECT(xa == xb, "%s: gathered state differs", label);
  rn_network_energy_terms(a, xa.data(), ea);
  rn_network_energy_terms(b, xb.data(), eb);
  for (int t = 0; t < RN_TERM_COUNT; ++t)
    EXPECT(ea[t] == eb[t], "%s: energy term %d: %.17g vs %.17g", label, t, ea[t], eb[t]);
  for (int r = 0; r < rn_network_num_rods(a); ++r) {
    const size_t nv = static_cast<size_t>(rn_network_rod_num_vertices(a, r));
    std::vector<double> d1a(3 * nv), d1b(3 * nv), d2a(3 * nv), d2b(3 * nv);
    rn_network_rod_frames(a, r, d1a.data(), d2a.data());
    rn_network_rod_frames(b, r, d1b.data(), d2b.data());
    EXPECT(d1a == d1b && d2a == d2b, "%s: rod %d directors differ", label, r);
  }
  for (int j = 0; j < rn_network_num_joints(a); ++j) {
    double Ra[9], Rb[9];
    rn_network_joint_rotation(a, j, Ra);
    rn_network_joint_rotation(b, j, Rb);
    EXPECT(std::equal(Ra, Ra + 9, Rb), "%s: joint %d rotation differs", label, j);
  }
}

void check_network(rn_context *ctx, const Builder &b, const char *label,
                   double max_share) {
  using namespace rodnet;
  auto comm = Tpetra::getDefaultComm();
  const int size = comm->getSize(), rank = comm->getRank();
  rn_network *g = nullptr;
  rn_network_create(ctx, &g);
  rn_network_set_graph_only(g);
  b(g);
  rn_network_finalize(g);
  int nr = 0, nj = 0;
  const int *nv = nullptr, *jp = nullptr, *jr = nullptr;
  rn_network_rod_graph(g, &nr, &nv, &nj, &jp, &jr);
  std::vector<int> rp(static_cast<size_t>(nr) + 1, 0), zero(rp.size(), 0);
  long cut = 0;
  EXPECT(rn_partition_rods(nr, nv, nj, jp, jr, size, rp.data(), &cut) == RN_OK,
         "partition");
  rn_network *part = build(ctx, b, size, rank, &rp, nr, nv, nj, jp, jr);
  rn_network *whole = build(ctx, b, 1, 0, nullptr, 0, nullptr, 0, nullptr, nullptr);
  rn_network *one = build(ctx, b, 1, 0, &zero, nr, nv, nj, jp, jr);
  const size_t n = rn_network_num_dofs(whole);
  const int64_t *wkeys = nullptr, *keys = nullptr;
  size_t n_owned = 0;
  rn_network_part_dofs(one, nullptr, &wkeys, nullptr);
  rn_network_part_dofs(part, &n_owned, &keys, nullptr);
  std::vector<size_t> widx(n_owned);
  for (size_t i = 0; i < n_owned; ++i)
    widx[i] = static_cast<size_t>(std::lower_bound(wkeys, wkeys + n, keys[i]) - wkeys);
  EXPECT(sum_all(static_cast<long>(n_owned)) == static_cast<long>(n), "%s: owned DOFs",
         label);
  if (size > 1 && max_share < 1.0)
    EXPECT(static_cast<double>(n_owned) <= max_share * static_cast<double>(n),
           "%s: rank owns %zu of %zu DOFs", label, n_owned, n);
  { // a one-process solver refuses a part (instead of solving it alone)
    rn_solve_report rep;
    EXPECT(rn_solve(part, nullptr, &rep) == RN_ERR_ARG &&
               std::strstr(rn_context_last_error(ctx), "needs the whole network"),
           "%s: rn_solve on a part: %s", label, rn_context_last_error(ctx));
  }
  {
    DistSystem sys(part, comm);
    EXPECT(sys.global_size() == static_cast<GO>(n), "%s: global size", label);
    TMV x(sys.map(), 1), gr(sys.map(), 1), v(sys.map(), 1), hv(sys.map(), 1);
    std::vector<double> xw(n), gw(n), vw(n), hw(n), x0(n);
    rn_network_get_dofs(whole, x0.data());
    uint64_t seed = 11;
    const void *graph = nullptr;
    for (int step = 0; step < 3; ++step) {
      for (size_t i = 0; i < n; ++i) {
        xw[i] = x0[i] + 2e-3 * rnd(seed);
        vw[i] = rnd(seed);
      }
      auto xd = x.getDataNonConst(0), vd = v.getDataNonConst(0);
      for (size_t i = 0; i < n_owned; ++i) {
        xd[static_cast<LO>(i)] = xw[widx[i]];
        vd[static_cast<LO>(i)] = vw[widx[i]];
      }
      double Ew = 0.0, E = 0.0, Eg = 0.0;
      rn_network_gradient(whole, xw.data(), &Ew, gw.data());
      rn_network_hvp(whole, xw.data(), vw.data(), hw.data());
      EXPECT(sys.energy(x, &E) == RN_OK, "%s: energy", label);
      EXPECT(sys.gradient(x, &Eg, gr) == RN_OK, "%s: gradient", label);
      EXPECT(std::fabs(E - Ew) <= 1e-12 * std::fabs(Ew), "%s: energy %.17g vs %.17g",
             label, E, Ew);
      EXPECT(std::fabs(Eg - Ew) <= 1e-12 * std::fabs(Ew), "%s: energy %.17g vs %.17g",
             label, Eg, Ew);
      sys.assemble_hessian(x);
      if (step == 0) graph = sys.hessian()->getCrsGraph().get();
      EXPECT(sys.hessian()->getCrsGraph().get() == graph, "%s: graph rebuilt", label);
      sys.hessian()->apply(v, hv);
      double eg = 0.0, eh = 0.0, sg = 0.0, sh = 0.0;
      auto gd = gr.getData(0), hd = hv.getData(0);
      for (size_t i = 0; i < n_owned; ++i) {
        eg = std::max(eg, std::fabs(gd[static_cast<LO>(i)] - gw[widx[i]]));
        eh = std::max(eh, std::fabs(hd[static_cast<LO>(i)] - hw[widx[i]]));
      }
      for (size_t i = 0; i < n; ++i) {
        sg = std::max(sg, std::fabs(gw[i]));
        sh = std::max(sh, std::fabs(hw[i]));
      }
      eg = max_all(eg);
      eh = max_all(eh);
      EXPECT(eg <= 1e-12 * sg, "%s step %d: gradient error %.3g of %.3g", label, step, eg,
             sg);
      EXPECT(eh <= 1e-12 * sh, "%s step %d: Hessian error %.3g of %.3g", label, step, eh,
             sh);
      { // the second-order stretching correction of the step v / 10 (the trust
        // region's, System::stretch_correction) sums over the parts to the whole's
        std::vector<double> sw(n), fw(n);
        for (size_t i = 0; i < n; ++i) sw[i] = 0.1 * vw[i];
        TMV s(sys.map(), 1), f(sys.map(), 1);
        s.update(0.1, v, 0.0);
        EXPECT(sys.has_stretch_correction(), "%s: no stretch correction", label);
        EXPECT(rn_network_stretch_correction(whole, xw.data(), sw.data(), fw.data()) ==
                       RN_OK &&
                   sys.stretch_correction(x, s, f) == RN_OK,
               "%s: stretch correction", label);
        double ef = 0.0, sf = 0.0;
        auto fd = f.getData(0);
        for (size_t i = 0; i < n_owned; ++i)
          ef = std::max(ef, std::fabs(fd[static_cast<LO>(i)] - fw[widx[i]]));
        for (size_t i = 0; i < n; ++i) sf = std::max(sf, std::fabs(fw[i]));
        ef = max_all(ef);
        EXPECT(sf > 0.0 && ef <= 1e-12 * sf,
               "%s step %d: stretch correction error %.3g of %.3g", label, step, ef, sf);
      }
      // accept the state everywhere: the updated owned values agree
      sys.accept(x);
      rn_network_update_reference(whole, xw.data());
      double ex = 0.0;
      auto xa = x.getData(0);
      for (size_t i = 0; i < n_owned; ++i)
        ex = std::max(ex, std::fabs(xa[static_cast<LO>(i)] - xw[widx[i]]));
      EXPECT(max_all(ex) == 0.0, "%s: accepted state differs by %.3g", label, ex);
    }
    // an error on the last rank only reaches all ranks as an exception
    {
      auto xd = x.getDataNonConst(0);
      if (rank == size - 1 && n_owned > 0) xd[0] = NAN;
      bool thrown = false;
      double E = 0.0;
      try {
        sys.energy(x, &E);
      } catch (const Error &e) {
        thrown = e.status() == RN_ERR_NOT_FINITE || n_owned == 0;
      }
      const long owners_last = sum_all(rank == size - 1 ? static_cast<long>(n_owned) : 0);
      if (owners_last > 0)
        EXPECT(thrown, "%s: the error did not reach rank %d", label, rank);
    }
  }
  // the parts' states gathered on rank 0 into a fresh whole network give the
  // results of the reference (updated in lockstep above)
  {
    rn_network *fresh =
        rank == 0 ? build(ctx, b, 1, 0, nullptr, 0, nullptr, 0, nullptr, nullptr)
                  : nullptr;
    EXPECT(rn_dist_gather_state(part, fresh) == RN_OK, "%s: gather: %s", label,
           rn_context_last_error(ctx));
    if (rank == 0) compare_results(whole, fresh, label);
    rn_network_destroy(&fresh);
  }
  if (rank == 0)
    std::printf("%s: %zu DOFs over %d ranks, edge cut %ld\n", label, n, size, cut);
  rn_network_destroy(&one);
  rn_network_destroy(&whole);
  rn_network_destroy(&part);
  rn_network_destroy(&g);
}

} // namespace

int main(int argc, char **argv) {
  Tpetra::ScopeGuard guard(&argc, &argv);
  rank_ = Tpetra::getDefaultComm()->getRank();
  rn_context *ctx = nullptr;
  rn_context_create(&ctx);
  check_network(ctx, single_rod, "single rod", 1.0);
  check_network(ctx, independent, "independent rods", 1.0);
  check_network(
      ctx, [](rn_network *n) { grid(n, 4, 3, RN_JOINT_RIGID); }, "rigid grid", 0.55);
  check_network(
      ctx, [](rn_network *n) { grid(n, 5, 1, -1); }, "one-edge lattice", 0.55);
  check_network(ctx, elastic_frame, "elastic frame", 1.0);
  rn_context_destroy(&ctx);
  int bad = failures;
  MPI_Allreduce(&failures, &bad, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  if (rank_ == 0)
    std::printf("mpi_system: %d checks on rank 0, %d failed (all ranks)\n", checks, bad);
  return bad ? 1 : 0;
}
