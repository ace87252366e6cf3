/* bench_joints.c - time per joint of the whole-joint kernels (rnk_joint_*) by
 * valence, rigid and elastic joints, closed forms (jointq.c) against the jet
 * implementation they replaced (rnk_jet_joint_*, kept as the test oracle; its
 * HVP was the dense block times the direction, as the assembly did before).
 *
 * Per (model, valence) a batch of --joints joints of that valence (random rod
 * directions, perturbed states, stale reference frames, a couple on every
 * other joint) is evaluated --repeats times per operation; the CSV row has
 * the median and minimum seconds per joint.  Before timing, every closed-form
 * result is compared with the jets' (relative 1e-9; the tests hold them to
 * 1e-12): a mismatch or a failing evaluation makes the program fail (exit 1).
 * Timings are never asserted.
 *
 *   bench_joints [--valences 1,2,3,4,6,8,12] [--joints 200] [--repeats 7]
 *                [--impl closed,jets] [--models rigid,elastic] [--out FILE.csv]
 *
 * CSV: bench "joints", case "<model>-<impl>-<op>", size the valence; extra
 * columns model, impl, op, stencil (DOFs of the joint stencil), ns_median,
 * ns_min (nanoseconds per joint). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "rnk.h"

#define MAX_LIST 16

typedef struct joint_case {
  rnk_joint j;
  rnk_joint_end *ends;
  rnk_frame *refs;
  double *q;
  int n;
} joint_case;

static uint64_t rng = 0x6a017ULL;
static double rnd(void) { return rn_bench_rand(&rng); }

static void unit3(double v[3]) {
  double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  for (int k = 0; k < 3; ++k) v[k] /= l;
}

/* A joint of valence v at the origin: rods along random directions, rest
 * frames of the terminal edges, the state perturbed by 0.05 and the
 * reference frames turned a little off (stale). */
static int make_joint(joint_case *c, int v, int rigid, int couple) {
  memset(c, 0, sizeof *c);
  c->ends = calloc((size_t)v, sizeof *c->ends);
  c->refs = calloc((size_t)v, sizeof *c->refs);
  c->j.rigid = rigid;
  c->j.valence = v;
  c->j.ends = c->ends;
  c->j.refs = c->refs;
  c->n = (int)rnk_joint_stencil_size(&c->j);
  c->q = calloc((size_t)c->n, sizeof(double));
  if (!c->ends || !c->refs || !c->q) return -1;
  for (int i = 0; i < 9; ++i) c->j.Qhat[i] = c->j.f0[i] = (i % 4 == 0);
  int off = rigid ? 6 : 3;
  for (int k = 0; k < v; ++k) {
    double dir[3] = {rnd(), rnd(), rnd()}, a[3] = {rnd(), rnd(), rnd()}, t[3];
    unit3(dir);
    int side = k % 2;
    for (int i = 0; i < 3; ++i) t[i] = side == 0 ? -dir[i] : dir[i];
    double d = a[0] * t[0] + a[1] * t[1] + a[2] * t[2];
    for (int i = 0; i < 3; ++i) a[i] -= d * t[i];
    unit3(a);
    rnk_joint_end *e = &c->ends[k];
    e->side = side;
    memcpy(e->cbar, t, sizeof t);
    memcpy(e->cbar + 3, a, sizeof a);
    e->cbar[6] = t[1] * a[2] - t[2] * a[1];
    e->cbar[7] = t[2] * a[0] - t[0] * a[2];
    e->cbar[8] = t[0] * a[1] - t[1] * a[0];
    e->bend = (rnk_bend_param){.B = {1.0, 0.1, 2.0}, .kbar = {0, 0}, .vlen = 0.05};
    e->twist = (rnk_twist_param){.beta = 0.8, .taubar = 0, .vlen = 0.05, .ref_twist = 0};
    memcpy(c->refs[k].t, t, sizeof t);
    memcpy(c->refs[k].a1, a, sizeof a);
    for (int i = 0; i < 3; ++i) c->q[off + 4 * k + i] = 0.1 * dir[i];
  }
  for (int i = 0; i < c->n; ++i) c->q[i] += 0.005 * rnd();
  for (int k = 0; k < v; ++k) {
    double *t = c->refs[k].t, *a = c->refs[k].a1;
    for (int i = 0; i < 3; ++i) t[i] += 0.05 * rnd();
    unit3(t);
    double d = a[0] * t[0] + a[1] * t[1] + a[2] * t[2];
    for (int i = 0; i < 3; ++i) a[i] -= d * t[i];
    unit3(a);
  }
  if (couple) {
    double m[3] = {rnd(), rnd(), rnd()}, p[3] = {rnd(), rnd(), rnd()};
    unit3(m);
    double d = m[0] * p[0] + m[1] * p[1] + m[2] * p[2];
    for (int i = 0; i < 3; ++i) p[i] -= d * m[i];
    unit3(p);
    memcpy(c->j.M, m, sizeof m);
    memcpy(c->j.couple_p, p, sizeof p);
  }
  return 0;
}

static void free_joint(joint_case *c) {
  free(c->ends);
  free(c->refs);
  free(c->q);
}

enum { OP_ENERGY, OP_GRAD, OP_HESS, OP_HVP, N_OPS };
static const char *op_names[N_OPS] = {"energy", "grad", "hess", "hvp"};

/* One evaluation; out holds n * n + n doubles, v the direction. */
static int eval(int jets, int op, const joint_case *c, double *work, const double *v,
                double *out) {
  double E;
  switch (op) {
  case OP_ENERGY:
    return jets ? rnk_jet_joint_energy(c->q, &c->j, work, &E)
                : rnk_joint_energy(c->q, &c->j, work, &E);
  case OP_GRAD:
    return jets ? rnk_jet_joint_grad(c->q, &c->j, work, &E, out)
                : rnk_joint_grad(c->q, &c->j, work, &E, out);
  case OP_HESS:
    return jets ? rnk_jet_joint_hess(c->q, &c->j, work, out)
                : rnk_joint_hess(c->q, &c->j, work, out);
  default:
    if (!jets) return rnk_joint_hvp(c->q, &c->j, work, v, out);
    { /* what the assembly did before: the block times the direction */
      int st = rnk_jet_joint_hess(c->q, &c->j, work, out + c->n);
      if (st == RNK_OK) rnk_block_mv(c->n, out + c->n, v, out);
      return st;
    }
  }
}

static double max_abs(int n, const double *a) {
  double m = 0;
  for (int i = 0; i < n; ++i) m = fmax(m, fabs(a[i]));
  return m;
}

/* Closed forms against jets on every joint of the batch. */
static int check_batch(joint_case *b, int nb, double *work, const double *v, double *o1,
                       double *o2) {
  for (int i = 0; i < nb; ++i) {
    int n = b[i].n;
    for (int op = OP_GRAD; op < N_OPS; ++op) {
      int m = op == OP_HESS ? n * n : n;
      if (eval(0, op, &b[i], work, v, o1) || eval(1, op, &b[i], work, v, o2)) {
        fprintf(stderr, "bench_joints: evaluation failed (joint %d, %s)\n", i,
                op_names[op]);
        return -1;
      }
      double s = fmax(max_abs(m, o2), 1.0); /* valence-1 elastic: all zero */
      for (int k = 0; k < m; ++k)
        if (!(fabs(o1[k] - o2[k]) <= 1e-9 * s)) {
          fprintf(stderr, "bench_joints: closed form and jets differ (joint %d, %s)\n", i,
                  op_names[op]);
          return -1;
        }
    }
  }
  return 0;
}

static int usage(const char *msg) {
  rn_bench_usage(
      "bench_joints", msg,
      "usage: bench_joints [--valences 1,2,3,4,6,8,12] "
      "[--joints 200] [--repeats 7] [--impl closed,jets] [--models rigid,elastic]\n"
      "       [--out FILE.csv]\n");
  return 1;
}

typedef struct joints_opts {
  long val[MAX_LIST];
  int nval, nb, repeats, impl_closed, impl_jets, model_rigid, model_elastic;
  const char *out;
} joints_opts;

/* 0 to run, 1 for --help (usage printed), -1 on a bad option (usage printed). */
static int parse_args(int argc, char **argv, joints_opts *o) {
  static const long valences[] = {1, 2, 3, 4, 6, 8, 12};
  memset(o, 0, sizeof *o);
  memcpy(o->val, valences, sizeof valences);
  o->nval = 7;
  o->nb = 200;
  o->repeats = 7;
  o->impl_closed = o->impl_jets = o->model_rigid = o->model_elastic = 1;
  for (int i = 1; i < argc; ++i) {
    const char *a = argv[i], *x = i + 1 < argc ? argv[i + 1] : NULL;
    if (!strcmp(a, "--help") || !strcmp(a, "-h")) return usage("joint kernel timing"), 1;
    if (!x) return usage("missing value after an option"), -1;
    ++i;
    if (!strcmp(a, "--valences")) {
      if ((o->nval = rn_bench_parse_list(x, o->val, MAX_LIST)) < 1)
        return usage("bad --valences"), -1;
    } else if (!strcmp(a, "--joints")) {
      if ((o->nb = atoi(x)) < 1) return usage("bad --joints"), -1;
    } else if (!strcmp(a, "--repeats")) {
      if ((o->repeats = atoi(x)) < 1) return usage("bad --repeats"), -1;
    } else if (!strcmp(a, "--impl")) {
      o->impl_closed = strstr(x, "closed") != NULL;
      o->impl_jets = strstr(x, "jets") != NULL;
      if (!o->impl_closed && !o->impl_jets) return usage("bad --impl"), -1;
    } else if (!strcmp(a, "--models")) {
      o->model_rigid = strstr(x, "rigid") != NULL;
      o->model_elastic = strstr(x, "elastic") != NULL;
      if (!o->model_rigid && !o->model_elastic) return usage("bad --models"), -1;
    } else if (!strcmp(a, "--out")) {
      o->out = x;
    } else {
      return usage("unknown option"), -1;
    }
  }
  return 0;
}

/* Times one operation of one implementation on the batch and writes its CSV row;
 * t holds the repeats.  0 if ok. */
static int time_op(FILE *f, const joints_opts *o, joint_case *b, int rigid, int jets,
                   int op, double *work, const double *vd, double *o1, double *t) {
  const int v = b[0].j.valence, n = b[0].n;
  const int nrun = jets && v >= 8 ? (o->nb + 3) / 4 : o->nb; /* the jets are slow */
  int rc = 0;
  for (int r = 0; r < o->repeats; ++r) {
    double t0 = rn_bench_now();
    for (int i = 0; i < nrun; ++i)
      if (eval(jets, op, &b[i], work, vd, o1)) rc = 1;
    t[r] = (rn_bench_now() - t0) / nrun;
  }
  double med, mn;
  rn_bench_stats(t, o->repeats, &med, &mn);
  char name[64];
  snprintf(name, sizeof name, "%s-%s-%s", rigid ? "rigid" : "elastic",
           jets ? "jets" : "closed", op_names[op]);
  rn_bench_csv_begin(f, "joints", name, v, o->repeats, med, mn);
  fprintf(f, ",%s,%s,%s,%d,%.1f,%.1f\n", rigid ? "rigid" : "elastic",
          jets ? "jets" : "closed", op_names[op], n, med * 1e9, mn * 1e9);
  fprintf(stderr, "%-28s valence %2d  %10.0f ns per joint\n", name, v, med * 1e9);
  return rc;
}

/* A batch of joints of valence v: checked (closed forms against jets), then every
 * operation of every implementation asked for timed.  0 if ok. */
static int bench_valence(FILE *f, const joints_opts *o, int rigid, int v, double *t) {
  const int nb = o->nb;
  int rc = 0;
  joint_case *b = calloc((size_t)nb, sizeof *b);
  size_t nwork = 0;
  for (int i = 0; i < nb && !rc; ++i) {
    if (make_joint(&b[i], v, rigid, i % 2)) rc = 1;
    size_t w1 = rnk_joint_work_size(&b[i].j), w2 = rnk_jet_joint_work_size(&b[i].j);
    nwork = w1 > nwork ? w1 : nwork;
    nwork = w2 > nwork ? w2 : nwork;
  }
  int n = b[0].n;
  double *work = malloc(sizeof(double) * nwork), *o1 = calloc((size_t)(n * n + n), 8),
         *o2 = calloc((size_t)(n * n + n), 8), *vd = malloc(sizeof(double) * (size_t)n);
  for (int i = 0; i < n; ++i) vd[i] = rnd();
  if (!rc && (!work || !o1 || !o2 || !vd || check_batch(b, nb, work, vd, o1, o2))) rc = 1;
  for (int jets = 0; jets <= 1 && !rc; ++jets) {
    if ((jets && !o->impl_jets) || (!jets && !o->impl_closed)) continue;
    for (int op = 0; op < N_OPS && !rc; ++op)
      rc = time_op(f, o, b, rigid, jets, op, work, vd, o1, t);
  }
  for (int i = 0; i < nb; ++i) free_joint(&b[i]);
  free(b);
  free(work);
  free(o1);
  free(o2);
  free(vd);
  return rc;
}

int main(int argc, char **argv) {
  joints_opts o;
  int rc = parse_args(argc, argv, &o);
  if (rc) return rc > 0 ? 0 : 1;
  FILE *f = o.out ? fopen(o.out, "w") : stdout;
  if (!f) return usage("cannot open --out");
  rn_bench_csv_header(f, "model,impl,op,stencil,ns_median,ns_min");
  double *t = malloc(sizeof(double) * (size_t)o.repeats);
  for (int rigid = 1; rigid >= 0 && !rc; --rigid)
    for (int iv = 0; iv < o.nval && !rc && (rigid ? o.model_rigid : o.model_elastic);
         ++iv)
      rc = bench_valence(f, &o, rigid, (int)o.val[iv], t);
  free(t);
  if (f != stdout) fclose(f);
  return rc;
}
