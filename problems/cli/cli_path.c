/* cli_path.c - `rodnet path SCENE.json -o PATH.csv [options]`: equilibrium path
 * by pseudo-arclength continuation in the load factor or under displacement
 * control of one vertex or joint coordinate (rn_path_follow;
 * docs/path-following.md). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/atomic_file.h"
#include "cli/cli.h"
#include "io/num_format.h"
#include "rodnet_solve.h"
#include "scene/scene.h"

#ifndef RN_PLOT_PATH_SCRIPT
#define RN_PLOT_PATH_SCRIPT "plot_path.py"
#endif
#ifndef RN_PYTHON3
#define RN_PYTHON3 "python3"
#endif

static const char path_help[] =
    "Usage: rodnet path SCENE.json -o PATH.csv [options]\n"
    "\n"
    "Follows the equilibrium path of a scene by pseudo-arclength continuation, past\n"
    "limit points and snap-backs, and writes one CSV row per point (completely or\n"
    "not at all).  The start is solved first: under load control at the load factor\n"
    "--start, under displacement control at --load-factor.  The lowest eigenvalue\n"
    "of the (constrained) Hessian at every point gives the stability; limit points\n"
    "and bifurcations are located and written as extra rows.\n"
    "\n"
    "Options:\n"
    "  -o, --output FILE        the path as CSV (required)\n"
    "      --control SPEC       load (default): continuation in the load factor;\n"
    "                           vertex:ROD:I:C or vertex:I:C (rod 0), joint:J:C:\n"
    "                           displacement control of coordinate C (x, y, z) of\n"
    "                           vertex I of rod ROD (name or index) or of joint J\n"
    "      --monitor SPEC       under load control: the coordinate written as control\n"
    "                           and displacement (default: the most loaded one)\n"
    "      --steps N            steps at most (default 200)\n"
    "      --arclength DS       first arclength step (default 0.01; RMS position\n"
    "                           changes over the structure's size, angles, the\n"
    "                           load factor or the controlled coordinate / size)\n"
    "      --max-arclength DS   largest step (default 0.05)\n"
    "      --to VALUE           stop where the load factor (default 1) or the\n"
    "                           controlled coordinate reaches VALUE\n"
    "      --direction +1|-1    sign of the first change of the parameter\n"
    "      --start LAMBDA       load control: the load factor to start at (default 0)\n"
    "      --load-factor LAMBDA displacement control: the fixed load factor (default 1)\n"
    "      --branch-switch      leave the first bifurcation along the critical\n"
    "                           eigenvector (--branch-sign -1: the other way)\n"
    "      --branch-sign +1|-1\n"
    "      --no-eigenvalues     skip the lowest eigenvalue (no stability, no events)\n"
    "      --factorization KIND auto, banded, sparse or cholmod (also spelt\n"
    "                           --factorisation)\n"
    "      --plot PNG           plot the path (python3 with matplotlib)\n"
    "  -q, --quiet              no progress on stderr, no summary on stdout\n"
    "  -h, --help               show this help\n"
    "\n"
    "CSV columns: step, event (point, limit, bifurcation, branch-switch),\n"
    "load_factor, control, displacement, force (conjugate force of the controlled\n"
    "coordinate, or the applied load at the monitored one), energy,\n"
    "lowest_eigenvalue, eigenvalue_scale, stability (stable, unstable, critical,\n"
    "unknown), arclength, corrector_iterations.\n"
    "\n"
    "Exit status: 0 done, 1 the path stopped early (the corrector failed down to\n"
    "the smallest step, or --to was given and not reached) or the start did not\n"
    "converge, 2 usage error, 3 bad scene, control or output path (or --to at or\n"
    "behind the start in the direction of the first step), 4 solver error or failed\n"
    "plot.\n";

#ifndef RN_HAVE_SOLVER
/* Without the solver: the help, else the refusal (status 5). */
int rn_cli_path(int argc, char **argv) {
  for (int i = 1; i < argc; i++)
    if (strcmp(argv[i], "-h") == 0 || strcmp(argv[i], "--help") == 0) {
      fputs(path_help, stdout);
      return RN_EXIT_OK;
    }
  return rn_cli_no_solver("path");
}
#else

typedef struct path_args {
  const char *scene, *output, *plot, *control, *monitor;
  rn_path_options opt;
  double start, load_factor;
  int quiet;
  int has_start, has_load_factor, has_ds, has_ds_max, has_branch_sign; /* given */
} path_args;

/* The files the command reads and writes (cli.h). */
static int path_files(const path_args *a, rn_cli_file *f) {
  const rn_cli_file files[] = {{"the scene file", a->scene, NULL, RN_CLI_IN},
                               {"-o", a->output, NULL, RN_CLI_OUT},
                               {"--plot", a->plot, NULL, RN_CLI_OUT}};
  memcpy(f, files, sizeof files);
  return (int)(sizeof files / sizeof files[0]);
}

static int parse_sign(const char *opt, const char *v, double *out) {
  if (strcmp(v, "1") == 0 || strcmp(v, "+1") == 0) {
    *out = 1.0;
    return 0;
  }
  if (strcmp(v, "-1") == 0) {
    *out = -1.0;
    return 0;
  }
  return rn_cli_usage_error("path", "%s: expected +1 or -1, got '%s'", opt, v);
}

/* --factorization (or --factorisation) NAME; returns 0, a usage exit code, or 1
 * if argv[*i] is another option. */
static int parse_factorization(int argc, char **argv, int *i, rn_path_options *o) {
  const char *v = NULL;
  int m = rn_cli_option_value("path", argc, argv, i, "--factorisation", NULL, &v);
  if (m < 0) return RN_EXIT_USAGE;
  if (!m) m = rn_cli_option_value("path", argc, argv, i, "--factorization", NULL, &v);
  if (m < 0) return RN_EXIT_USAGE;
  if (!m) return 1;
  if (rn_factorization_from_name(v, &o->factorization) != RN_OK)
    return rn_cli_usage_error("path",
                              "--factorization: expected auto, banded, sparse or "
                              "cholmod, got '%s'",
                              v);
  return 0;
}

/* The options with a value; returns 0, a usage exit code, or 1 if not one of
 * them. */
static int parse_valued(int argc, char **argv, int *i, path_args *a) {
  const char *v = NULL;
  int m;
  rn_path_options *o = &a->opt;
#define VALUED(name, short_name)                                                  \
  if ((m = rn_cli_option_value("path", argc, argv, i, name, short_name, &v)) < 0) \
    return RN_EXIT_USAGE;                                                         \
  if (m)
  VALUED("--output", "-o") {
    a->output = v;
    return 0;
  }
  VALUED("--control", NULL) {
    a->control = v;
    return 0;
  }
  VALUED("--monitor", NULL) {
    a->monitor = v;
    return 0;
  }
  VALUED("--plot", NULL) {
    a->plot = v;
    return 0;
  }
  VALUED("--steps", NULL) {
    return rn_cli_parse_int("path", "--steps", v, 1, 1000000, &o->max_steps);
  }
  VALUED("--arclength", NULL) {
    a->has_ds = 1;
    return rn_cli_parse_double("path", "--arclength", v, 0.0, &o->ds) ? RN_EXIT_USAGE : 0;
  }
  VALUED("--max-arclength", NULL) {
    a->has_ds_max = 1;
    return rn_cli_parse_double("path", "--max-arclength", v, 0.0, &o->ds_max)
               ? RN_EXIT_USAGE
               : 0;
  }
  VALUED("--to", NULL) {
    return rn_cli_parse_double("path", "--to", v, -HUGE_VAL, &o->target) ? RN_EXIT_USAGE
                                                                         : 0;
  }
  VALUED("--direction", NULL) { return parse_sign("--direction", v, &o->direction); }
  VALUED("--branch-sign", NULL) {
    a->has_branch_sign = 1;
    return parse_sign("--branch-sign", v, &o->branch_sign);
  }
  VALUED("--start", NULL) {
    a->has_start = 1;
    return rn_cli_parse_double("path", "--start", v, -HUGE_VAL, &a->start) ? RN_EXIT_USAGE
                                                                           : 0;
  }
  VALUED("--load-factor", NULL) {
    a->has_load_factor = 1;
    return rn_cli_parse_double("path", "--load-factor", v, -HUGE_VAL, &a->load_factor)
               ? RN_EXIT_USAGE
               : 0;
  }
#undef VALUED
  return parse_factorization(argc, argv, i, o);
}

/* The options of the other control mode (or of --branch-switch) would be
 * ignored: a usage error; 0 otherwise. */
static int check_modes(const path_args *a) {
  const int load_control = !a->control || strcmp(a->control, "load") == 0;
  if (load_control && a->has_load_factor)
    return rn_cli_usage_error("path",
                              "--load-factor applies to displacement control "
                              "(--control vertex:... or joint:...); under load control "
                              "the path starts at --start");
  if (!load_control && a->has_start)
    return rn_cli_usage_error("path",
                              "--start applies to load control; under displacement "
                              "control the load factor is fixed by --load-factor");
  if (!load_control && a->monitor)
    return rn_cli_usage_error("path", "--monitor applies to --control load only");
  if (load_control && !isnan(a->opt.target) &&
      !(a->opt.target >= 0.0 && a->opt.target <= 1.0))
    return rn_cli_usage_error("path", "--to: the target load factor must be in [0, 1]");
  if (a->has_branch_sign && !a->opt.branch_switch)
    return rn_cli_usage_error("path", "--branch-sign applies to --branch-switch only");
  return 0;
}

/* The steps: the first (--arclength) at most the largest (--max-arclength);
 * the one given alone moves the other's default.  0 or a usage error. */
static int settle_steps(path_args *a) {
  rn_path_options *o = &a->opt;
  if (a->has_ds && a->has_ds_max && o->ds_max < o->ds)
    return rn_cli_usage_error("path",
                              "--max-arclength %g is below --arclength %g: the largest "
                              "step must be at least the first",
                              o->ds_max, o->ds);
  if (a->has_ds && o->ds_max < o->ds) o->ds_max = o->ds;
  if (a->has_ds_max && o->ds > o->ds_max) o->ds = o->ds_max;
  if (o->ds < o->ds_min)
    return rn_cli_usage_error("path",
                              "--%sarclength %g is below the smallest step %g (steps "
                              "shorter than that stop the path)",
                              a->has_ds ? "" : "max-", o->ds, o->ds_min);
  return 0;
}

/* The start's load factors in [0, 1]; branch switching needs the
 * eigenvalues.  0 or a usage error. */
static int check_start(const path_args *a) {
  if (!(a->start >= 0.0 && a->start <= 1.0))
    return rn_cli_usage_error("path", "--start: the load factor must be in [0, 1]");
  if (!(a->load_factor >= 0.0 && a->load_factor <= 1.0))
    return rn_cli_usage_error("path", "--load-factor: must be in [0, 1]");
  if (a->opt.branch_switch && !a->opt.eigenvalues)
    return rn_cli_usage_error("path", "--branch-switch needs the eigenvalues");
  return 0;
}

static int parse_args(int argc, char **argv, path_args *a) {
  memset(a, 0, sizeof *a);
  rn_path_options_default(&a->opt);
  a->start = 0.0;
  a->load_factor = 1.0;
  for (int i = 1; i < argc; i++) {
    const char *s = argv[i];
    if (strcmp(s, "-h") == 0 || strcmp(s, "--help") == 0) {
      fputs(path_help, stdout);
      return -1;
    }
    if (strcmp(s, "-q") == 0 || strcmp(s, "--quiet") == 0) {
      a->quiet = 1;
      continue;
    }
    if (strcmp(s, "--branch-switch") == 0) {
      a->opt.branch_switch = 1;
      continue;
    }
    if (strcmp(s, "--no-eigenvalues") == 0) {
      a->opt.eigenvalues = 0;
      continue;
    }
    int rc = parse_valued(argc, argv, &i, a);
    if (rc != 1) {
      if (rc) return rc;
      continue;
    }
    if (s[0] == '-' && s[1] != '\0')
      return rn_cli_usage_error("path", "unknown option '%s'", s);
    if (a->scene)
      return rn_cli_usage_error("path", "more than one scene given ('%s' and '%s')",
                                a->scene, s);
    a->scene = s;
  }
  static const char *const valued[] = {"--output|-o",
                                       "--control",
                                       "--monitor",
                                       "--plot",
                                       "--steps",
                                       "--arclength",
                                       "--max-arclength",
                                       "--to",
                                       "--direction",
                                       "--branch-sign",
                                       "--start",
                                       "--load-factor",
                                       "--factorization|--factorisation",
                                       NULL};
  int rc = rn_cli_check_repeats("path", argc, argv, valued);
  if (rc) return rc;
  if (!a->scene) return rn_cli_usage_error("path", "missing the scene file");
  if (!a->output) return rn_cli_usage_error("path", "missing -o PATH.csv");
  if ((rc = check_modes(a)) || (rc = settle_steps(a)) || (rc = check_start(a))) return rc;
  rn_cli_file files[3];
  return rn_cli_check_files("path", files, path_files(a, files));
}

/* Index (possibly negative, from the end) or name of a rod or joint. */
static int find_index(const char *s, int count,
                      int (*by_name)(const rn_scene *, const char *),
                      const rn_scene *scene) {
  char *end = NULL;
  long v = strtol(s, &end, 10);
  if (end != s && *end == '\0') {
    if (v < 0) v += count;
    return v >= 0 && v < count ? (int)v : -1;
  }
  return by_name(scene, s);
}

/* The coordinate C: x, y, z or 0, 1, 2; -1 if none. */
static int component_index(const char *c) {
  if (strcmp(c, "x") == 0 || strcmp(c, "0") == 0) return 0;
  if (strcmp(c, "y") == 0 || strcmp(c, "1") == 0) return 1;
  if (strcmp(c, "z") == 0 || strcmp(c, "2") == 0) return 2;
  return -1;
}

/* The reduced DOF of coordinate comp of joint (>= 0), else of the vertex of
 * rod; -1 if it is not a free DOF, -2 out of memory (message printed). */
static long position_dof(rn_network *net, int comp, int joint, int rod, int vertex) {
  size_t n = rn_network_num_dofs(net);
  rn_dof_info *info = malloc((n ? n : 1) * sizeof *info);
  if (!info || rn_network_dof_info(net, info) != RN_OK) {
    free(info);
    fprintf(stderr, "rodnet path: out of memory\n");
    return -2;
  }
  long found = -1;
  for (size_t i = 0; i < n && found < 0; i++)
    if (info[i].kind == RN_DOF_POSITION && info[i].component == comp &&
        (joint >= 0 ? info[i].joint == joint
                    : (info[i].rod == rod && info[i].index == vertex)))
      found = (long)i;
  free(info);
  return found;
}

/* The reduced DOF that SPEC (vertex:ROD:I:C, vertex:I:C, joint:J:C) names;
 * -1 with a message on stderr. */
static long find_dof(const char *file, const char *opt, const char *spec,
                     const rn_scene *scene) {
  rn_network *net = rn_scene_network(scene);
  char buf[256];
  char *part[4] = {NULL, NULL, NULL, NULL};
  int np = 0;
  if (strlen(spec) >= sizeof buf) goto bad;
  strcpy(buf, spec);
  for (char *p = buf, *q; np < 4 && p; p = q) {
    q = strchr(p, ':');
    if (q) *q++ = '\0';
    part[np++] = p;
    if (!q) break;
  }
  int comp = component_index(part[np - 1]);
  if (comp < 0) goto bad;
  int rod = -1, joint = -1, vertex = 0;
  if (strcmp(part[0], "vertex") == 0 && (np == 3 || np == 4)) {
    rod = np == 4
              ? find_index(part[1], rn_network_num_rods(net), rn_scene_find_rod, scene)
              : 0;
    if (rod < 0) {
      fprintf(stderr, "rodnet path: %s: %s %s: no rod '%s'\n", file, opt, spec, part[1]);
      return -1;
    }
    int nv = rn_network_rod_num_vertices(net, rod);
    char *end = NULL;
    long v = strtol(part[np - 2], &end, 10);
    if (end == part[np - 2] || *end != '\0') goto bad;
    if (v < 0) v += nv;
    if (v < 0 || v >= nv) {
      fprintf(stderr, "rodnet path: %s: %s %s: rod %d has %d vertices\n", file, opt, spec,
              rod, nv);
      return -1;
    }
    vertex = (int)v;
  } else if (strcmp(part[0], "joint") == 0 && np == 3) {
    joint = find_index(part[1], rn_network_num_joints(net), rn_scene_find_joint, scene);
    if (joint < 0) {
      fprintf(stderr, "rodnet path: %s: %s %s: no joint '%s'\n", file, opt, spec,
              part[1]);
      return -1;
    }
  } else {
    goto bad;
  }
  long found = position_dof(net, comp, joint, rod, vertex);
  if (found == -1)
    fprintf(stderr,
            "rodnet path: %s: %s %s: that coordinate is not a free DOF (it is fixed by a "
            "support, or the vertex is a rod end at a joint: name the joint)\n",
            file, opt, spec);
  return found < 0 ? -1 : found;
bad:
  fprintf(stderr,
          "rodnet path: %s: %s '%s': expected load, vertex:ROD:I:C, vertex:I:C or "
          "joint:J:C with C one of x, y, z\n",
          file, opt, spec);
  return -1;
}

typedef struct path_rows {
  rn_path_point *p;
  size_t n, cap;
  int quiet, oom;
  const char *path; /* the CSV being written (messages) */
} path_rows;

static const char *stability_name(int s) {
  switch (s) {
  case 1:
    return "stable";
  case -1:
    return "unstable";
  case 0:
    return "critical";
  default:
    return "unknown";
  }
}

static int on_point(void *user, const rn_path_point *pt) {
  path_rows *r = user;
  if (r->n == r->cap) {
    size_t cap = r->cap ? 2 * r->cap : 256;
    rn_path_point *p = realloc(r->p, cap * sizeof *p);
    if (!p) {
      r->oom = 1;
      return 1;
    }
    r->p = p;
    r->cap = cap;
  }
  r->p[r->n++] = *pt;
  if (!r->quiet)
    fprintf(stderr,
            "path %4d %-13s load %.6g  control %.6g  force %.6g  E %.6g  eig %.3e "
            "(%s)  it %d\n",
            pt->step, rn_path_event_name(pt->event), pt->load_factor, pt->control,
            pt->force, pt->energy, pt->lowest_eigenvalue, stability_name(pt->stability),
            pt->corrector_iterations);
  return 0;
}

static rn_status write_csv(FILE *f, void *user, rn_context *ctx) {
  const path_rows *r = user;
  /* every number finite, but the eigenvalue columns: "nan" there is documented
   * (--no-eigenvalues; docs/path-following.md) */
  rn_num_check chk = {0, 0.0, ""};
  for (size_t i = 0; i < r->n && !chk.bad; i++) {
    const rn_path_point *p = &r->p[i];
    static const char *const col[] = {"load_factor", "control", "displacement",
                                      "force",       "energy",  "arclength"};
    const double v[] = {p->load_factor, p->control, p->displacement,
                        p->force,       p->energy,  p->arclength};
    for (int k = 0; k < 6 && !chk.bad; k++) {
      char field[96];
      snprintf(field, sizeof field, "column %s of step %d", col[k], p->step);
      if (!isfinite(v[k])) rn_num_checked(&chk, field, v[k]);
    }
  }
  if (chk.bad) {
    char msg[512];
    return rn_context_set_error(ctx, RN_ERR_NOT_FINITE, "%s",
                                rn_num_check_message(&chk, r->path, msg, sizeof msg));
  }
  fputs("step,event,load_factor,control,displacement,force,energy,lowest_eigenvalue,"
        "eigenvalue_scale,stability,arclength,corrector_iterations\n",
        f);
  for (size_t i = 0; i < r->n; i++) {
    const rn_path_point *p = &r->p[i];
    fprintf(f, "%d,%s,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%s,%.17g,%d\n", p->step,
            rn_path_event_name(p->event), p->load_factor, p->control, p->displacement,
            p->force, p->energy, p->lowest_eigenvalue, p->eigenvalue_scale,
            stability_name(p->stability), p->arclength, p->corrector_iterations);
  }
  return RN_OK;
}

/* The controlled and the monitored DOF of the scene into opt; 0 or the exit
 * status (message printed). */
static int control_dofs(const path_args *a, const rn_scene *scene, rn_path_options *opt) {
  if (a->control && strcmp(a->control, "load") != 0) {
    long dof = find_dof(a->scene, "--control", a->control, scene);
    if (dof < 0) return RN_EXIT_INPUT;
    opt->control = RN_PATH_DOF;
    opt->dof = (size_t)dof;
  } else if (!isnan(opt->target) && !(opt->target >= 0.0 && opt->target <= 1.0)) {
    return rn_cli_usage_error("path", "--to: the target load factor must be in [0, 1]");
  }
  if (a->monitor) {
    if (opt->control == RN_PATH_DOF)
      return rn_cli_usage_error("path", "--monitor applies to --control load only");
    long dof = find_dof(a->scene, "--monitor", a->monitor, scene);
    if (dof < 0) return RN_EXIT_INPUT;
    opt->monitor = dof;
  }
  return 0;
}

/* The start: an equilibrium at the starting load factor; 0 or the exit status
 * (message printed). */
static int solve_start(const path_args *a, rn_context *ctx, rn_scene *scene,
                       const rn_path_options *opt) {
  rn_network *net = rn_scene_network(scene);
  rn_solve_options so;
  rn_solve_options_default(&so);
  rn_scene_apply_solver(scene, &so);
  /* (a scene is read at load factor 1 with its prescribed DOFs where the input
   * puts them: rn_solve steps them from there; set another factor only) */
  const double lf0 = opt->control == RN_PATH_DOF ? a->load_factor : a->start;
  rn_status st =
      lf0 != rn_network_load_factor(net) ? rn_network_set_load_factor(net, lf0) : RN_OK;
  rn_solve_report sr;
  if (!st) st = rn_solve(net, &so, &sr);
  if (st) {
    fprintf(stderr, "rodnet path: %s: the starting solve failed (%s): %s\n", a->scene,
            rn_status_name(st), rn_context_last_error(ctx));
    return RN_EXIT_INTERNAL;
  }
  if (!sr.converged) {
    fprintf(stderr, "rodnet path: %s: the starting solve did not converge (%s)\n",
            a->scene, rn_solve_stop_name(sr.stop));
    return RN_EXIT_NOT_CONVERGED;
  }
  return 0;
}

/* The report on stdout. */
static void print_report(const path_args *a, const rn_path_report *rep) {
  printf("rodnet path: %s: %d steps, %d points, stop %s, %d limit point(s), %d "
         "bifurcation(s), %ld corrector iterations, %.3g s\n",
         a->scene, rep->steps, rep->points, rn_path_stop_name(rep->stop),
         rep->limit_points, rep->bifurcations, rep->corrector_iterations, rep->time_s);
  if (rep->limit_points)
    printf("  first limit point: load factor %.10g, control %.10g, force %.10g\n",
           rep->limit_load_factor, rep->limit_control, rep->limit_force);
  if (rep->bifurcations)
    printf("  first bifurcation: load factor %.10g, control %.10g, force %.10g\n",
           rep->bifurcation_load_factor, rep->bifurcation_control,
           rep->bifurcation_force);
  printf("  wrote %s\n", a->output);
}

static int run(const path_args *a, rn_context *ctx, rn_scene *scene, path_rows *rows) {
  rn_network *net = rn_scene_network(scene);
  rn_path_options opt = a->opt;
  int rc = control_dofs(a, scene, &opt);
  if (rc || (rc = solve_start(a, ctx, scene, &opt))) return rc;
  opt.callback = on_point;
  opt.user = rows;
  rn_path_report rep;
  rn_status st = rn_path_follow(net, &opt, &rep);
  if (rows->oom) {
    fprintf(stderr, "rodnet path: out of memory\n");
    return RN_EXIT_INTERNAL;
  }
  if (st) {
    fprintf(stderr, "rodnet path: %s: path following failed (%s): %s\n", a->scene,
            rn_status_name(st), rn_context_last_error(ctx));
    return st == RN_ERR_ARG ? RN_EXIT_INPUT : RN_EXIT_INTERNAL;
  }
  rows->path = a->output;
  if ((st = rn_file_write_atomic(ctx, a->output, write_csv, rows))) {
    fprintf(stderr, "rodnet path: %s\n", rn_context_last_error(ctx));
    return RN_EXIT_INPUT;
  }
  if (!a->quiet) print_report(a, &rep);
  if (a->plot &&
      rn_cli_plot("RODNET_PLOT_PATH", RN_PLOT_PATH_SCRIPT, a->output, a->plot) != 0) {
    fprintf(stderr,
            "rodnet path: the plot %s failed (%s %s with matplotlib; RODNET_PYTHON and "
            "RODNET_PLOT_PATH override them); %s is written\n",
            a->plot, getenv("RODNET_PYTHON") ? getenv("RODNET_PYTHON") : RN_PYTHON3,
            getenv("RODNET_PLOT_PATH") ? getenv("RODNET_PLOT_PATH") : RN_PLOT_PATH_SCRIPT,
            a->output);
    return RN_EXIT_INTERNAL;
  }
  if (!isnan(a->opt.target) && rep.stop != RN_PATH_STOP_TARGET &&
      rep.stop != RN_PATH_STOP_STEP_MIN) {
    /* --to given and not reached (the step-min stop has its own status) */
    const rn_path_point *end = rows->n ? &rows->p[rows->n - 1] : NULL;
    fprintf(stderr,
            "rodnet path: %s: the path did not reach --to %.10g: it stopped (%s) at %s "
            "%.10g after %d steps; %s holds the path so far\n",
            a->scene, a->opt.target, rn_path_stop_name(rep.stop),
            opt.control == RN_PATH_DOF ? "control" : "load factor",
            end ? (opt.control == RN_PATH_DOF ? end->control : end->load_factor) : NAN,
            rep.steps, a->output);
    return RN_EXIT_NOT_CONVERGED;
  }
  return rep.stop == RN_PATH_STOP_STEP_MIN ? RN_EXIT_NOT_CONVERGED : RN_EXIT_OK;
}

int rn_cli_path(int argc, char **argv) {
  path_args a;
  int rc = parse_args(argc, argv, &a);
  if (rc) return rc < 0 ? RN_EXIT_OK : rc;
  rn_context *ctx = NULL;
  if (rn_context_create(&ctx) != RN_OK) {
    fprintf(stderr, "rodnet path: out of memory\n");
    return RN_EXIT_INTERNAL;
  }
  rn_scene *scene = NULL;
  path_rows rows = {NULL, 0, 0, a.quiet, 0, NULL};
  rn_cli_file files[3];
  rn_status st = RN_OK;
  /* every output writable before anything is computed */
  if ((rc = rn_cli_probe_outputs("path", files, path_files(&a, files)))) {
    /* message printed */
  } else if ((st = rn_scene_load(ctx, a.scene, &scene))) {
    fprintf(stderr, "%s\n", rn_context_last_error(ctx));
    rc = rn_cli_load_exit_code(st);
  } else {
    rc = run(&a, ctx, scene, &rows);
  }
  free(rows.p);
  rn_scene_destroy(&scene);
  rn_context_destroy(&ctx);
  return rc;
}
#endif /* RN_HAVE_SOLVER */
