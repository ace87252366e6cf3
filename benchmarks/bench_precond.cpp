// bench_precond.cpp - preconditioners of the Newton systems of rod lattices
// (issue 7, docs/solvers.md "Preconditioners for networks"): the rod-level domain
// decomposition with its direct and AMG coarse solves against MueLu on the whole
// Hessian, Ifpack2 additive Schwarz and the exact sparse factorisation.
//
//   bench_precond [--kind honeycomb] [--cells 10,30] [--models rigid,elastic]
//                 [--edges-per-rod 8] [--load stretch-x:1e-3]
//                 [--precond dd,dd-direct,dd-amg,muelu,ifpack2,frosch,factor] [--tol
//                 1e-8]
//                 [--max-its 3000] [--repeats 1] [--amg-xml FILE] [--out FILE.csv]
//
// For each lattice (`rodnet generate` scene, period 1, E = 1, nu = 0.3, circle r =
// 1/50) and preconditioner: the Newton system H s = -g at the initial state (the
// face displaced by the load, the rest at rest) solved by preconditioned MINRES
// (rodnet's Belos driver, relative tolerance --tol in the preconditioner's norm):
// setup time (first: with the symbolic work; second: numeric only, what every
// further Newton step pays), MINRES iterations and time, time per application, the
// preconditioner's memory per vertex and the process's peak resident size, the true
// relative residual.  Under mpirun the DOFs are distributed by rods
// (shim_cxx/system/replicated_system.hpp: every rank holds the whole network, so memory
// is not divided).  Prints a line per run and appends CSV rows; asserts only that the
// solves converge.
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Core.hpp>

#include "pc/impls/dd/dd_preconditioner.hpp"
#include "pc/impls/frosch/frosch.hpp"
#include "pc/impls/ifpack2/ifpack2.hpp"
#include "pc/impls/muelu/muelu.hpp"
#include "bench_config.h"
#include "krylov/minres.hpp"
#include "system/replicated_system.hpp"
#include "base/shim_error.hpp"
#include "factor/sparse_cholesky.hpp"
#include "factor/spd_factor.hpp"

extern "C" {
#include "bench_util.h"
#include "generate/lattice.h"
#include "generate/lattice_scene.h"
#include "scene/scene.h"
}

namespace {

using namespace rodnet;
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

double peak_rss_mb() {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return static_cast<double>(ru.ru_maxrss) / 1024.0;
}

struct Opts {
  rn_lattice_kind kind = RN_LATTICE_HONEYCOMB;
  std::vector<long> cells{10};
  std::vector<int> models{RN_JOINT_RIGID};
  int edges = 8, repeats = 1, max_its = 3000;
  rn_lattice_load_kind load = RN_LLOAD_STRETCH;
  int load_axis = 0;
  double load_value = 1e-3, tol = 1e-8;
  std::string load_text = "stretch-x:1e-3", out, amg_xml;
  bool newton = false;
  std::vector<std::string> precs{"dd", "muelu", "ifpack2", "factor"};
};

std::vector<std::string> split(const std::string &s) {
  std::vector<std::string> v;
  size_t a = 0;
  while (a <= s.size()) {
    size_t b = s.find(',', a);
    if (b == std::string::npos) b = s.size();
    if (b > a) v.push_back(s.substr(a, b - a));
    a = b + 1;
  }
  return v;
}

bool parse_load(const std::string &v, Opts &o) {
  static const char *kinds[4] = {"stretch-", "compress-", "pull-", "grip-"};
  static const rn_lattice_load_kind load[4] = {RN_LLOAD_STRETCH, RN_LLOAD_STRETCH,
                                               RN_LLOAD_PULL, RN_LLOAD_GRIP};
  for (int k = 0; k < 4; ++k) {
    const size_t len = std::strlen(kinds[k]);
    if (v.compare(0, len, kinds[k]) != 0) continue;
    if (v.size() < len + 3 || v[len] < 'x' || v[len] > 'z' || v[len + 1] != ':')
      return false;
    char *end = nullptr;
    const double x = std::strtod(v.c_str() + len + 2, &end);
    if (*end || !std::isfinite(x)) return false;
    o.load = load[k];
    o.load_axis = v[len] - 'x';
    o.load_value = k == 1 ? -x : x;
    o.load_text = v;
    return true;
  }
  return false;
}

int usage(const char *msg) {
  return rn_bench_usage(
      "bench_precond", msg,
      "usage: bench_precond [--kind honeycomb] [--cells 10,30] [--models rigid,elastic]\n"
      "  [--edges-per-rod 8] [--load stretch-x:1e-3] "
      "[--precond dd,dd-direct,dd-amg,muelu,ifpack2,frosch,factor]\n  [--tol 1e-8] "
      "[--max-its 3000] [--repeats 1] [--amg-xml FILE] [--newton] [--out FILE.csv]\n");
}

int parse(int argc, char **argv, Opts &o) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--newton") {
      o.newton = true;
      continue;
    }
    if (i + 1 >= argc) return usage(("missing value of " + a).c_str());
    const std::string v = argv[++i];
    if (a == "--kind") {
      if (rn_lattice_kind_from_name(v.c_str(), &o.kind)) return usage("bad --kind");
    } else if (a == "--cells") {
      o.cells.clear();
      for (const std::string &c : split(v)) o.cells.push_back(std::atol(c.c_str()));
    } else if (a == "--models") {
      o.models.clear();
      for (const std::string &m : split(v)) {
        if (m == "rigid")
          o.models.push_back(RN_JOINT_RIGID);
        else if (m == "elastic")
          o.models.push_back(RN_JOINT_ELASTIC);
        else
          return usage("bad --models");
      }
    } else if (a == "--edges-per-rod") {
      o.edges = std::atoi(v.c_str());
    } else if (a == "--load") {
      if (!parse_load(v, o)) return usage("bad --load");
    } else if (a == "--precond") {
      o.precs = split(v);
    } else if (a == "--tol") {
      o.tol = std::atof(v.c_str());
    } else if (a == "--max-its") {
      o.max_its = std::atoi(v.c_str());
    } else if (a == "--repeats") {
      o.repeats = std::max(1, std::atoi(v.c_str()));
    } else if (a == "--amg-xml") {
      o.amg_xml = v;
    } else if (a == "--out") {
      o.out = v;
    } else {
      return usage(("unknown option " + a).c_str());
    }
  }
  return 0;
}

// The exact sparse factorisation of the (replicated) Hessian as a preconditioner
// (one rank): rodnet's Cholesky of H + sigma D, sigma the smallest decade that
// factors (spd_factor.hpp), as the solver's trust region uses it.
class FactorPrec : public Preconditioner {
public:
  explicit FactorPrec(ReplicatedSystem &sys) : sys_(sys) {}
  void setup(System &) override {
    const auto t0 = Clock::now();
    Problem &p = sys_.problem();
    if (!f_) f_ = make_spd_factor(p, RN_FACTOR_AUTO);
    const std::vector<double> d = diagonal_on_pattern(p, hessian_metric(p));
    shift_ = factor_shifted(*f_, p, 0.0, d.data());
    stats_.setups++;
    stats_.setup_seconds += since(t0);
    stats_.bytes = choose_factor_kind(p, RN_FACTOR_AUTO) == RN_FACTOR_BANDED
                       ? 8.0 * static_cast<double>(p.size() * (p.bandwidth() + 1))
                       : 8.0 * static_cast<double>(p.sparse_analysis()->factor_entries());
  }
  Teuchos::RCP<const Tpetra::Operator<>> inverse() const override {
    return Teuchos::rcp(new Op(this));
  }
  std::string name() const override { return "factor"; }

private:
  struct Op : public Tpetra::Operator<> {
    explicit Op(const FactorPrec *p) : p_(p) {}
    Teuchos::RCP<const TMap> getDomainMap() const override { return p_->sys_.map(); }
    Teuchos::RCP<const TMap> getRangeMap() const override { return p_->sys_.map(); }
    void apply(const TMV &X, TMV &Y, Teuchos::ETransp, double alpha,
               double beta) const override {
      const auto t0 = Clock::now();
      auto x = X.getLocalViewHost(Tpetra::Access::ReadOnly);
      auto y = Y.getLocalViewHost(Tpetra::Access::ReadWrite);
      std::vector<double> w(x.extent(0));
      for (size_t i = 0; i < w.size(); ++i) w[i] = x(i, 0);
      p_->f_->solve(w.data());
      for (size_t i = 0; i < w.size(); ++i)
        y(i, 0) = beta == 0.0 ? alpha * w[i] : beta * y(i, 0) + alpha * w[i];
      auto *st = const_cast<PreconditionerStats *>(&p_->stats());
      st->applies++;
      st->apply_seconds += since(t0);
    }
    const FactorPrec *p_;
  };
  ReplicatedSystem &sys_;
  std::unique_ptr<SpdFactor> f_;
  double shift_ = 0.0;
};

class CrsOp : public VectorOperator {
public:
  explicit CrsOp(Teuchos::RCP<const Tpetra::Operator<>> A) : A_(std::move(A)) {}
  void apply(const MV &x, MV &y) const override { A_->apply(x, y); }

private:
  Teuchos::RCP<const Tpetra::Operator<>> A_;
};

rn_scene *load_lattice(rn_context *ctx, const Opts &o, long cells, int model, int rank) {
  const int c[3] = {static_cast<int>(cells), static_cast<int>(cells),
                    static_cast<int>(cells)};
  rn_lattice *lat = nullptr;
  rn_lattice_scene sc{};
  rn_scene *scene = nullptr;
  char path[256];
  std::snprintf(path, sizeof path, "bench_precond_scene_%d_%ld.json", rank,
                static_cast<long>(getpid()));
  sc.description = "bench_precond";
  sc.edges_per_rod = o.edges;
  sc.joint_model = model;
  sc.E = 1.0;
  sc.nu = 0.3;
  sc.shape = RN_LSEC_CIRCLE;
  sc.section[0] = 1.0 / 50.0;
  sc.load = o.load;
  sc.load_axis = o.load_axis;
  sc.load_value = o.load_value;
  rn_status s = rn_lattice_build(ctx, o.kind, c, 1.0, &lat);
  if (!s) s = rn_lattice_write_scene(ctx, path, lat, &sc);
  rn_lattice_destroy(&lat);
  if (!s) s = rn_scene_load(ctx, path, &scene);
  std::remove(path);
  if (s) {
    std::fprintf(stderr, "bench_precond: lattice: %s\n", rn_context_last_error(ctx));
    return nullptr;
  }
  return scene;
}

struct Run {
  double setup1 = 0, setup2 = 0, minres_s = 0, apply_s = 0, bytes = 0, residual = 0;
  double coarse_shift = 0, coarse_flops = 0;
  long long coarse_rows = 0;
  int its = 0;
  bool converged = false;
  std::string coarse = "-";
};

std::unique_ptr<Preconditioner> make_prec(ReplicatedSystem &sys, const std::string &name,
                                          const Opts &o) {
  std::unique_ptr<Preconditioner> P;
  if (name == "factor") {
    P.reset(new FactorPrec(sys));
  } else if (name == "muelu") {
    P.reset(new MueluPreconditioner(sys.rigid_body_modes()));
  } else if (name == "frosch") {
    P.reset(new FroschPreconditioner(sys.rigid_body_modes()));
  } else if (name == "ifpack2") {
    P.reset(new SchwarzPreconditioner);
  } else if (name.compare(0, 2, "dd") == 0) {
    DdOptions d;
    d.coarse = name == "dd" ? DdOptions::Coarse::Auto
                            : (name == "dd-amg" ? DdOptions::Coarse::Amg
                                                : DdOptions::Coarse::Direct);
    d.amg_xml = o.amg_xml;
    P.reset(new DdPreconditioner(d));
  }
  if (!P) throw Error(RN_ERR_ARG, "bench_precond: unknown preconditioner " + name);
  return P;
}

Run run_one(ReplicatedSystem &sys, const std::string &name, const Opts &o, const TMV &g) {
  Run r;
  std::unique_ptr<Preconditioner> P = make_prec(sys, name, o);
  auto t0 = Clock::now();
  P->setup(sys);
  r.setup1 = since(t0);
  t0 = Clock::now();
  P->setup(sys); // numeric only (what each further Newton step pays)
  r.setup2 = since(t0);
  if (auto *dd = dynamic_cast<DdPreconditioner *>(P.get())) {
    r.coarse_rows = dd->coarse_rows();
    r.coarse = dd->coarse_solver();
    r.coarse_shift = dd->coarse_shift();
    r.coarse_flops = dd->coarse_flops();
  }
  auto map = sys.map();
  TMV b(map, 1), s(map, 1), Hs(map, 1);
  b.update(-1.0, g, 0.0);
  MinresSolver solver(map, o.tol, o.max_its);
  CrsOp A(sys.hessian()), M(P->inverse());
  const long applies0 = P->stats().applies;
  const double apply_s0 = P->stats().apply_seconds;
  t0 = Clock::now();
  MinresResult res = solver.solve(A, M, b, s);
  r.minres_s = since(t0);
  r.its = res.iterations;
  r.converged = res.converged;
  const long na = P->stats().applies - applies0;
  r.apply_s =
      na > 0 ? (P->stats().apply_seconds - apply_s0) / static_cast<double>(na) : 0.0;
  double bytes = P->stats().bytes;
  Teuchos::reduceAll(*map->getComm(), Teuchos::REDUCE_SUM, bytes,
                     Teuchos::outArg(r.bytes));
  sys.hessian()->apply(s, Hs);
  Hs.update(-1.0, b, 1.0);
  r.residual = Hs.getVector(0)->norm2() / b.getVector(0)->norm2();
  return r;
}

// A Newton solve to equilibrium with preconditioned MINRES steps (--newton): from the
// rest state at load factor 0, the linearised load-increment predictor (as rn_solve's,
// docs/solvers.md) to load factor 1, then Newton steps H s = -g (MINRES to --tol)
// with a backtracking (Armijo) line search on the energy, until |g| <= 1e-9 of the
// out-of-balance force of the displaced rest state (rn_solve's default test).  Not
// rodnet's solver (the Newton-Krylov trust region is): a measurement of what the
// preconditioners cost in a whole solve.
struct NewtonRun {
  int newton = 0, minres = 0;
  double total = 0, hessian = 0, setup = 0, minres_s = 0, gratio = 0;
  bool converged = false, predictor = false;
};

double norm2(const TMV &v) { return v.getVector(0)->norm2(); }
double dot1(const TMV &a, const TMV &b) {
  Teuchos::Array<double> d(1);
  a.dot(b, d());
  return d[0];
}

NewtonRun run_newton(ReplicatedSystem &sys, const std::string &name, const Opts &o) {
  NewtonRun r;
  const auto t_start = Clock::now();
  auto map = sys.map();
  TMV x(map, 1), g(map, 1), dg(map, 1), s(map, 1), b(map, 1), xt(map, 1);
  std::unique_ptr<Preconditioner> P = make_prec(sys, name, o);
  MinresSolver solver(map, o.tol, o.max_its);
  auto step = [&](const TMV &rhs) { // s = H^-1 rhs at the assembled H
    auto t0 = Clock::now();
    P->setup(sys);
    r.setup += since(t0);
    CrsOp A(sys.hessian()), M(P->inverse());
    t0 = Clock::now();
    MinresResult res = solver.solve(A, M, rhs, s);
    r.minres_s += since(t0);
    r.minres += res.iterations;
  };
  auto assemble = [&]() {
    const auto t0 = Clock::now();
    sys.assemble_hessian(x);
    r.hessian += since(t0);
  };
  // Predictor from the rest state.
  sys.set_load_factor(0.0);
  sys.get_state(x);
  double E = 0.0, Et = 0.0;
  sys.gradient(x, &E, g);
  assemble();
  sys.load_increment(x, 0.0, 1.0, dg);
  sys.set_load_factor(1.0);
  b.update(-1.0, g, -1.0, dg, 0.0);
  step(b);
  sys.gradient(x, &E, g);
  const double f = norm2(g); // out-of-balance force of the displaced rest state
  xt.update(1.0, x, 1.0, s, 0.0);
  if (sys.energy(xt, &Et) == RN_OK && Et < E) {
    x.assign(xt);
    sys.accept(x);
    r.predictor = true;
  }
  for (r.newton = 0; r.newton < 50; ++r.newton) {
    sys.gradient(x, &E, g);
    r.gratio = norm2(g) / f;
    if (r.gratio <= 1e-9) {
      r.converged = true;
      break;
    }
    assemble();
    b.update(-1.0, g, 0.0);
    step(b);
    const double slope = dot1(g, s);
    double alpha = 1.0;
    for (int k = 0; k < 40; ++k, alpha *= 0.5) {
      xt.update(1.0, x, alpha, s, 0.0);
      if (sys.energy(xt, &Et) == RN_OK && Et <= E + 1e-4 * alpha * std::min(slope, 0.0))
        break;
    }
    x.assign(xt);
    sys.accept(x);
  }
  r.total = since(t_start);
  return r;
}

// One lattice (cells, joint model) as the lines and CSV rows describe it.
struct Case {
  const Opts &o;
  long cells;
  const char *model;
  long long dofs;
  long vertices;
  int rods, joints, nranks;
};

// The columns every row starts with, up to the preconditioner's name (and its comma).
void put_row_start(FILE *out, const Case &c, const char *bench, const std::string &pname,
                   double median, double mn) {
  const char *kind = rn_lattice_kind_name(c.o.kind);
  const std::string name = std::string(kind) + "-" + c.model + "-" + pname;
  rn_bench_csv_begin_ranks(out, c.nranks, bench, name.c_str(), static_cast<long>(c.dofs),
                           c.o.repeats, median, mn);
  std::fprintf(out, ",%s,%ld,%s,%d,%s,%ld,%d,%d,%s,", kind, c.cells, c.model, c.o.edges,
               c.o.load_text.c_str(), c.vertices, c.rods, c.joints, pname.c_str());
}

// --newton: repeated Newton solves from the scene's state (initial); the line and
// the row.  0 if the last solve converged.
int newton_case(FILE *out, ReplicatedSystem &sys, rn_network *net,
                const rn_state *initial, const Case &c, const std::string &pname,
                int rank) {
  std::vector<double> totals;
  NewtonRun r;
  for (int k = 0; k < c.o.repeats; ++k) {
    rn_network_state_restore(net, initial);
    r = run_newton(sys, pname, c.o);
    totals.push_back(r.total);
  }
  std::sort(totals.begin(), totals.end());
  const double rss = peak_rss_mb();
  if (rank == 0) {
    std::printf("%s %ldx %s, %lld DOFs, %ld vertices: %-9s Newton %d (predictor %d), "
                "MINRES %d (%.1f per step), total %.2f s (Hessian %.2f, setup %.2f, "
                "MINRES %.2f), |g|/f %.1e, peak RSS %.0f MB (%.0f B/vertex)%s\n",
                rn_lattice_kind_name(c.o.kind), c.cells, c.model, c.dofs, c.vertices,
                pname.c_str(), r.newton, r.predictor ? 1 : 0, r.minres,
                static_cast<double>(r.minres) / (r.newton + 1), r.total, r.hessian,
                r.setup, r.minres_s, r.gratio, rss,
                rss * 1048576.0 / static_cast<double>(c.vertices),
                r.converged ? "" : " NOT CONVERGED");
    std::fflush(stdout);
    if (out) {
      put_row_start(out, c, "precond-newton", pname, totals[totals.size() / 2],
                    totals.front());
      std::fprintf(out, "-,0,0,%.6e,0,%.6e,%d,%.6e,0,0,%.1f,%.1f,%d,%.3e,%d,%d,0\n",
                   r.hessian, r.setup, r.minres, r.minres_s,
                   rss * 1048576.0 / static_cast<double>(c.vertices), rss,
                   r.converged ? 1 : 0, r.gratio, r.newton, r.predictor ? 1 : 0);
      std::fflush(out);
    }
  }
  return r.converged ? 0 : 1;
}

// One Newton system H s = -g (g at the initial state, th the Hessian's assembly
// time) solved with the preconditioner pname, --repeats times; the line and the row.
// 0 if the last solve converged.
int system_case(FILE *out, ReplicatedSystem &sys, const TMV &g, double th, const Case &c,
                const std::string &pname, int rank) {
  std::vector<double> totals;
  Run r;
  for (int k = 0; k < c.o.repeats; ++k) {
    r = run_one(sys, pname, c.o, g);
    totals.push_back(r.setup2 + r.minres_s);
  }
  std::sort(totals.begin(), totals.end());
  const double median = totals[totals.size() / 2], mn = totals.front();
  if (rank == 0) {
    std::printf("%s %ldx %s, %lld DOFs, %ld vertices: %-9s setup %.3f / %.3f s, "
                "MINRES %d its %.3f s (apply %.2e s), %.0f B/vertex, coarse %s %lld "
                "(shift %g, %.1e flops), residual %.1e%s\n",
                rn_lattice_kind_name(c.o.kind), c.cells, c.model, c.dofs, c.vertices,
                pname.c_str(), r.setup1, r.setup2, r.its, r.minres_s, r.apply_s,
                r.bytes / static_cast<double>(c.vertices), r.coarse.c_str(),
                r.coarse_rows, r.coarse_shift, r.coarse_flops, r.residual,
                r.converged ? "" : " NOT CONVERGED");
    std::fflush(stdout);
    if (out) {
      put_row_start(out, c, "precond", pname, median, mn);
      std::fprintf(out,
                   "%s,%lld,%g,%.6e,%.6e,%.6e,%d,%.6e,%.6e,%.6e,%.3f,%.1f,%d,%.3e,0,0,"
                   "%.3e\n",
                   r.coarse.c_str(), r.coarse_rows, r.coarse_shift, th, r.setup1,
                   r.setup2, r.its, r.minres_s, r.apply_s, r.bytes,
                   r.bytes / static_cast<double>(c.vertices), peak_rss_mb(),
                   r.converged ? 1 : 0, r.residual, r.coarse_flops);
      std::fflush(out);
    }
  }
  return r.converged ? 0 : 1;
}

// Every preconditioner of --precond on the lattice (cells, model).  0 if ok.
int lattice_case(FILE *out, rn_context *ctx, const Opts &o,
                 const Teuchos::RCP<const Teuchos::Comm<int>> &comm, long cells,
                 int model) {
  const int rank = comm->getRank(), nranks = comm->getSize();
  rn_scene *scene = load_lattice(ctx, o, cells, model, rank);
  if (!scene) return 1;
  rn_network *net = rn_scene_network(scene);
  rn_state *initial = nullptr; // every run starts from the scene's state
  if (rn_network_state_save(net, &initial)) {
    rn_scene_destroy(&scene);
    return 1;
  }
  int rc = 0;
  try {
    ReplicatedSystem sys(net, comm);
    TMV x(sys.map(), 1), g(sys.map(), 1);
    sys.get_state(x);
    double E = 0.0;
    sys.gradient(x, &E, g);
    auto t0 = Clock::now();
    sys.assemble_hessian(x);
    const double th = since(t0);
    const Case c{o,
                 cells,
                 model == RN_JOINT_RIGID ? "rigid" : "elastic",
                 static_cast<long long>(sys.global_size()),
                 rn_scene_num_vertices(scene),
                 rn_network_num_rods(net),
                 rn_network_num_joints(net),
                 nranks};
    for (const std::string &pname : o.precs) {
      if (pname == "factor" && nranks > 1) continue;
      if (o.newton ? newton_case(out, sys, net, initial, c, pname, rank)
                   : system_case(out, sys, g, th, c, pname, rank))
        rc = 1;
    }
  } catch (const std::exception &e) {
    if (rank == 0) std::fprintf(stderr, "bench_precond: %s\n", e.what());
    rc = 1;
  }
  rn_state_destroy(&initial);
  rn_scene_destroy(&scene);
  return rc;
}

// Rank 0 with --out: the CSV file opened for appending, its header written if it
// is new.  nullptr otherwise; *rc = 1 if it cannot be opened.
FILE *open_csv(const Opts &o, int rank, int *rc) {
  if (rank != 0 || o.out.empty()) return nullptr;
  FILE *probe = std::fopen(o.out.c_str(), "r");
  const bool fresh = probe == nullptr;
  if (probe) std::fclose(probe);
  FILE *out = std::fopen(o.out.c_str(), "a");
  if (!out) {
    std::fprintf(stderr, "bench_precond: cannot write %s\n", o.out.c_str());
    *rc = 1;
    return nullptr;
  }
  if (fresh)
    rn_bench_csv_header(out, "kind,cells,model,edges_per_rod,load,vertices,rods,joints,"
                             "precond,coarse_solver,coarse_rows,coarse_shift,hessian_s,"
                             "setup1_s,setup2_s,minres_its,minres_s,apply_s,bytes,"
                             "bytes_per_vertex,peak_rss_mb,converged,residual");
  return out;
}

} // namespace

int main(int argc, char **argv) {
  Tpetra::ScopeGuard guard(&argc, &argv);
  int rc = 0;
  {
    Opts o;
    if ((rc = parse(argc, argv, o))) return rc;
    auto comm = Tpetra::getDefaultComm();
    FILE *out = open_csv(o, comm->getRank(), &rc);
    if (rc) return rc;
    rn_context *ctx = nullptr;
    rn_context_create(&ctx);
    for (long cells : o.cells)
      for (int model : o.models)
        if (lattice_case(out, ctx, o, comm, cells, model)) rc = 1;
    rn_context_destroy(&ctx);
    if (out) std::fclose(out);
  }
  return rc;
}
