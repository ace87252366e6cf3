// bench_dist.cpp - work per rank of a distributed Newton step (issue 7, section 5):
// run under `mpirun -np P`.  The scene is read as in `rodnet solve` (graph pass,
// METIS partition, each rank's part), then the evaluations of one Newton step of a
// distributed solver are repeated on the distributed System
// (shim_cxx/system/dist_system.hpp): gradient (energy, ghost import, gradient export),
// Hessian assembly (CSR values, overlap matrix export), the preconditioner's setup and
// the Newton system H s = -g by preconditioned MINRES to the relative tolerance 1e-8
// (--precond NAME, default dd, the solve's default; --precond none: no linear solve), one
// trial energy and the accepted reference update.
//
// Rank 0 writes one CSV row per rank: the common columns (bench dist, case = scene
// name, size = global DOFs, ranks, median and min wall time per step over the
// repeats) and rank, owned_dofs, ghost_dofs, owned_stencils, owned_rods, ghost_rods,
// bytes_per_step (payload the rank sent in imports, exports and reductions per step,
// the preconditioner's own communication not included),
// edge_cut, rss_mb (resident memory after the steps: the part, its System and
// matrices) and peak_mb (the high-water mark, which includes the transient JSON tree
// of the scene that every rank parses) and bytes_per_matvec (what one Hessian apply,
// i.e. one Krylov iteration, sends: the ghost columns of x the other ranks import).  With
// --callgrind the step loop is bracketed by CALLGRIND_START_INSTRUMENTATION / STOP: run
// under `valgrind --tool=callgrind
// --instr-atstart=no` to count the instructions of the steps alone, per rank
// (benchmarks/bench_dist.sh).  Timings are reported, never asserted; the benchmark
// checks that every evaluation succeeds and that the energy is finite.
#include <mpi.h>
#include <valgrind/callgrind.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <Tpetra_Core.hpp>

extern "C" {
#include "bench_util.h"
#include "scene/scene.h"
}
#include "system/dist_system.hpp"
#include "krylov/minres.hpp"
#include "pc/preconditioner.hpp"
#include "rodnet_solve.h"
#include "newton/solvers.hpp"

namespace {

struct Opts {
  const char *scene = nullptr, *out = nullptr, *label = nullptr, *precond = "dd";
  int repeats = 5;
  bool callgrind = false;
};

int usage(const char *msg) {
  return rn_bench_usage(
      "bench_dist", msg,
      "usage: mpirun -np P bench_dist SCENE.json [--repeats N] "
      "[--label NAME] [--out CSV] [--precond NAME|none] [--callgrind]\n");
}

int parse(int argc, char **argv, Opts &o) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--repeats" && i + 1 < argc)
      o.repeats = std::atoi(argv[++i]);
    else if (a == "--out" && i + 1 < argc)
      o.out = argv[++i];
    else if (a == "--label" && i + 1 < argc)
      o.label = argv[++i];
    else if (a == "--precond" && i + 1 < argc)
      o.precond = argv[++i];
    else if (a == "--callgrind")
      o.callgrind = true;
    else if (a[0] != '-' && !o.scene)
      o.scene = argv[i];
    else
      return usage(("unknown argument " + a).c_str());
  }
  if (!o.scene) return usage("missing the scene");
  if (o.repeats < 1) return usage("--repeats must be >= 1");
  rn_preconditioner p;
  if (std::strcmp(o.precond, "none") != 0 && rn_preconditioner_from_name(o.precond, &p))
    return usage("unknown --precond");
  return 0;
}

// Graph pass, partition, part pass (as `rodnet solve` under mpirun).
rn_scene *load_part(rn_context *ctx, const char *path, int rank, int size, long *cut) {
  rn_scene_part sp;
  std::memset(&sp, 0, sizeof sp);
  sp.mode = RN_SCENE_GRAPH;
  rn_scene *graph = nullptr, *part = nullptr;
  if (rn_scene_load_part(ctx, path, &sp, &graph)) return nullptr;
  const int *nv, *jp, *jr;
  int nr, nj;
  rn_network_rod_graph(rn_scene_network(graph), &nr, &nv, &nj, &jp, &jr);
  std::vector<int> rp(static_cast<size_t>(nr) + 1);
  if (rn_partition_rods(nr, nv, nj, jp, jr, size, rp.data(), cut) == RN_OK) {
    sp.mode = RN_SCENE_PART;
    sp.nparts = size;
    sp.part = rank;
    sp.nrods = nr;
    sp.njoints = nj;
    sp.rod_nv = nv;
    sp.rod_part = rp.data();
    sp.joint_ptr = jp;
    sp.joint_rods = jr;
    rn_scene_load_part(ctx, path, &sp, &part);
  }
  rn_scene_destroy(&graph);
  return part;
}

// y = A x for MINRES from a Tpetra operator (the Hessian, a preconditioner's inverse).
class OpAdapter : public rodnet::VectorOperator {
public:
  explicit OpAdapter(const Tpetra::Operator<> &A) : A_(A) {}
  void apply(const rodnet::MV &x, rodnet::MV &y) const override { A_.apply(x, y); }

private:
  const Tpetra::Operator<> &A_;
};

// VmRSS and VmHWM of this process in MB (/proc/self/status; 0 if unknown).
void memory_mb(double *rss, double *peak) {
  *rss = *peak = 0.0;
  FILE *f = std::fopen("/proc/self/status", "r");
  if (!f) return;
  char line[256];
  while (std::fgets(line, sizeof line, f)) {
    long kb = 0;
    if (std::sscanf(line, "VmRSS: %ld kB", &kb) == 1)
      *rss = static_cast<double>(kb) / 1024.0;
    if (std::sscanf(line, "VmHWM: %ld kB", &kb) == 1)
      *peak = static_cast<double>(kb) / 1024.0;
  }
  std::fclose(f);
}

enum { NCOL = 13 }; // the columns of one rank's row (write_rows)

// The preconditioner o.precond names on sys (nullptr for "none"; *bad set if it
// cannot be built).
std::unique_ptr<rodnet::Preconditioner>
preconditioner(const rodnet::DistSystem &sys, const Opts &o, int rank, int *bad) {
  std::unique_ptr<rodnet::Preconditioner> prec;
  if (std::strcmp(o.precond, "none") != 0) {
    rn_solve_options opt;
    rn_solve_options_default(&opt);
    rn_preconditioner_from_name(o.precond, &opt.preconditioner);
    rn_preconditioner used;
    try {
      prec = rodnet::make_preconditioner(sys, opt, &used);
    } catch (const std::exception &e) {
      if (rank == 0) std::fprintf(stderr, "bench_dist: %s\n", e.what());
      *bad = 1;
    }
  }
  return prec;
}

// This rank's row of NCOL numbers (write_rows): its part, the bytes sent per step,
// the memory, the bytes a Hessian apply imports, the MINRES iterations per step.
std::vector<double> part_row(const rodnet::DistSystem &sys, rn_network *net, int rank,
                             double bytes, long cut, double minres_its) {
  rn_part_info info;
  rn_network_part_info(net, &info);
  std::vector<double> row = {static_cast<double>(rank),
                             static_cast<double>(info.owned_dofs),
                             static_cast<double>(info.ghost_dofs),
                             static_cast<double>(info.owned_stencils),
                             static_cast<double>(info.owned_rods),
                             static_cast<double>(info.ghost_rods),
                             bytes,
                             static_cast<double>(sys.global_size()),
                             static_cast<double>(cut),
                             0.0,
                             0.0,
                             0.0,
                             minres_its};
  memory_mb(&row[9], &row[10]);
  // a Krylov iteration's Hessian apply imports the ghost columns of x
  auto imp = sys.hessian()->getCrsGraph()->getImporter();
  row[11] = imp.is_null() ? 0.0 : 8.0 * static_cast<double>(imp->getNumExportIDs());
  return row;
}

// The repeated Newton step on this rank's part (gradient, Hessian, a preconditioned
// MINRES solve if o.precond is not "none", energy, accept): the step times in times,
// this rank's row of NCOL numbers, *bad set if anything failed.
std::vector<double> measure(rn_network *net, const Opts &o,
                            const Teuchos::RCP<const Teuchos::Comm<int>> &comm, long cut,
                            std::vector<double> &times, int *bad) {
  const int rank = comm->getRank();
  double minres_its = 0.0;
  rodnet::DistSystem sys(net, comm);
  rodnet::TMV x(sys.map(), 1), g(sys.map(), 1), s(sys.map(), 1);
  sys.get_state(x);
  std::unique_ptr<rodnet::Preconditioner> prec = preconditioner(sys, o, rank, bad);
  rodnet::MinresSolver minres(sys.map(), 1e-8, 1000);
  double E = 0.0;
  sys.gradient(x, &E, g); // warm-up: first-touch allocations, Kokkos views
  sys.assemble_hessian(x);
  const rodnet::CommStats before = sys.comm_stats();
  if (o.callgrind) CALLGRIND_START_INSTRUMENTATION;
  for (int r = 0; r < o.repeats; ++r) {
    comm->barrier();
    const double t0 = rn_bench_now();
    if (sys.gradient(x, &E, g) != RN_OK) *bad = 1;
    sys.assemble_hessian(x);
    if (prec) {
      prec->setup(sys);
      g.scale(-1.0);
      const rodnet::MinresResult mr =
          minres.solve(OpAdapter(*sys.hessian()), OpAdapter(*prec->inverse()), g, s);
      minres_its += mr.iterations;
      if (!mr.converged) *bad = 1;
    }
    double Et = 0.0;
    if (sys.energy(x, &Et) != RN_OK || !std::isfinite(Et)) *bad = 1;
    sys.accept(x);
    comm->barrier();
    times.push_back(rn_bench_now() - t0);
  }
  if (o.callgrind) CALLGRIND_STOP_INSTRUMENTATION;
  const double bytes = (sys.comm_stats().bytes_sent - before.bytes_sent) / o.repeats;
  return part_row(sys, net, rank, bytes, cut, minres_its / o.repeats);
}

// Rank 0: one CSV row per rank (rows: NCOL numbers per rank) with the median and
// minimum step time, appended to o.out (the header if the file is new) or stdout.
void write_rows(const Opts &o, int size, const std::vector<double> &rows,
                std::vector<double> &times) {
  double med = 0.0, mn = 0.0;
  rn_bench_stats(times.data(), static_cast<int>(times.size()), &med, &mn);
  FILE *f = o.out ? std::fopen(o.out, "a") : stdout;
  static const char *const extra =
      "rank,owned_dofs,ghost_dofs,owned_stencils,owned_rods,"
      "ghost_rods,bytes_per_step,edge_cut,rss_mb,peak_mb,bytes_per_matvec,precond,"
      "minres_its";
  if (f && (!o.out || std::ftell(f) == 0)) rn_bench_csv_header(f, extra);
  const std::string label = o.label ? o.label : o.scene;
  for (int q = 0; q < size && f; ++q) {
    const double *r = &rows[NCOL * static_cast<size_t>(q)];
    rn_bench_csv_begin_ranks(f, size, "dist", label.c_str(), static_cast<long>(r[7]),
                             o.repeats, med, mn);
    std::fprintf(f, ",%d,%.0f,%.0f,%.0f,%.0f,%.0f,%.0f,%.0f,%.1f,%.1f,%.0f,%s,%.1f\n", q,
                 r[1], r[2], r[3], r[4], r[5], r[6], r[8], r[9], r[10], r[11], o.precond,
                 r[12]);
  }
  if (f && o.out) std::fclose(f);
}

} // namespace

int main(int argc, char **argv) {
  Tpetra::ScopeGuard guard(&argc, &argv);
  Opts o;
  if (int rc = parse(argc, argv, o)) return rc;
  auto comm = Tpetra::getDefaultComm();
  const int rank = comm->getRank(), size = comm->getSize();
  rn_context *ctx = nullptr;
  rn_context_create(&ctx);
  long cut = 0;
  rn_scene *scene = load_part(ctx, o.scene, rank, size, &cut);
  if (rn_dist_agree(ctx, scene ? RN_OK : RN_ERR_PARSE) != RN_OK) {
    if (rank == 0) std::fprintf(stderr, "bench_dist: %s\n", rn_context_last_error(ctx));
    rn_scene_destroy(&scene);
    rn_context_destroy(&ctx);
    return 1;
  }
  int bad = 0;
  std::vector<double> times;
  const std::vector<double> row =
      measure(rn_scene_network(scene), o, comm, cut, times, &bad);
  std::vector<double> rows(NCOL * static_cast<size_t>(size));
  MPI_Gather(row.data(), NCOL, MPI_DOUBLE, rows.data(), NCOL, MPI_DOUBLE, 0,
             MPI_COMM_WORLD);
  int any_bad = bad;
  MPI_Allreduce(&bad, &any_bad, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  if (rank == 0) write_rows(o, size, rows, times);
  rn_scene_destroy(&scene);
  rn_context_destroy(&ctx);
  return any_bad;
}
