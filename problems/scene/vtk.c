/* vtk.c - .vtu writer (VTK XML UnstructuredGrid, ASCII).  Each data array is
 * one field: a function that fills the values of one rod, written rod after
 * rod (the field table is in vtk.h's order).  The stencil quantities that several
 * fields share (rn_network_rod_vertex_fields, rn_network_rod_strains,
 * rn_network_rod_frames) are computed once per rod before writing, 8 doubles per
 * interior vertex and 6 per edge.  The text goes through a 64 KiB buffer of the
 * writer's own (one fwrite per block, not per row). */
#include "scene/vtk.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/atomic_file.h"
#include "io/num_format.h"
#include "scene/vec3.h"

enum { VTK_VERTEX = 1, VTK_LINE = 3, N_WORK = 4, OUT_CAP = 1 << 16 };

typedef struct vtk_out {
  FILE *f;
  const rn_scene *scene;
  rn_network *net;
  int not_finite;
  double *val;          /* values of one rod, 9 * max vertices */
  double *work[N_WORK]; /* scratch, 3 * max vertices each */
  size_t *first;        /* per rod: index of its first interior vertex in the caches */
  double *vf;           /* per interior vertex i of a rod, in blocks of 5 (interior count)
                           per rod: moments (m1, m2), twisting moment, bending and twisting
                           energy, as rn_network_rod_vertex_fields returns them */
  double *kt;           /* blocks of 3 per rod: curvature (kappa1, kappa2), twist (tau) */
  double *fr;           /* per edge, in blocks of 6 (edge count) per rod: d1, then d2 */
  double *fi, *mi;      /* per edge (3 each, edges in rod order): internal force and
                           moment, rn_network_internal_forces */
  char *buf;            /* output not yet handed to f: len bytes of OUT_CAP */
  size_t len;
  const char *path;
  /* the array and rod (or joint) being written, for the message of a
   * non-finite value (the first is recorded, the file discarded) */
  const char *array;
  int rod, joint;
  rn_num_check chk;
} vtk_out;

/* Cached stencil fields of rod (vtk_out.vf): moment[2 n], twist_moment[n],
 * bend_energy[n], twist_energy[n], n the rod's interior vertices. */
static const double *rod_vertex_fields(const vtk_out *o, int rod) {
  return o->vf + 5 * o->first[rod];
}

static const double *rod_strains(const vtk_out *o, int rod) {
  return o->kt + 3 * o->first[rod];
}

/* Cached directors of rod: d1[3 ne], then d2[3 ne] (ne edges; the rod's first
 * edge has index first[rod] + rod among all edges). */
static const double *rod_frames(const vtk_out *o, int rod) {
  return o->fr + 6 * (o->first[rod] + (size_t)rod);
}

/* Fills the caches: one rn_network_rod_vertex_fields and one rn_network_rod_strains
 * call per rod, one rn_network_internal_forces call. */
static rn_status cache_stencil_fields(vtk_out *o) {
  const int nrods = rn_network_num_rods(o->net);
  size_t total = 0;
  o->first = malloc(((size_t)nrods + 1) * sizeof *o->first);
  if (!o->first) return RN_ERR_ALLOC;
  for (int r = 0; r < nrods; r++) {
    o->first[r] = total;
    total += (size_t)rn_network_rod_num_vertices(o->net, r) - 2;
  }
  o->first[nrods] = total;
  o->vf = malloc((5 * total + 1) * sizeof *o->vf);
  o->kt = malloc((3 * total + 1) * sizeof *o->kt);
  o->fr = malloc((6 * (total + (size_t)nrods) + 1) * sizeof *o->fr);
  o->fi = malloc((3 * (total + (size_t)nrods) + 1) * sizeof *o->fi);
  o->mi = malloc((3 * (total + (size_t)nrods) + 1) * sizeof *o->mi);
  if (!o->vf || !o->kt || !o->fr || !o->fi || !o->mi) return RN_ERR_ALLOC;
  rn_status st = rn_network_internal_forces(o->net, o->fi, o->mi);
  for (int r = 0; r < nrods && !st; r++) {
    const size_t n = o->first[r + 1] - o->first[r];
    double *v = o->vf + 5 * o->first[r], *k = o->kt + 3 * o->first[r];
    double *d = o->fr + 6 * (o->first[r] + (size_t)r);
    st = rn_network_rod_vertex_fields(o->net, r, v, v + 2 * n, v + 3 * n, v + 4 * n);
    if (!st) st = rn_network_rod_strains(o->net, r, NULL, k, k + 2 * n);
    if (!st) st = rn_network_rod_frames(o->net, r, d, d + 3 * (n + 1));
  }
  return st;
}

/* Fills o->val with the values of one rod (count * ncomp). */
typedef rn_status (*vtk_fill)(vtk_out *o, int rod, double *val);

typedef struct vtk_field {
  const char *name;
  const char *type; /* VTK type of the array */
  int ncomp;
  int on_edges; /* cell data (else point data) */
  vtk_fill fill;
} vtk_field;

/* ---- small vector helpers ------------------------------------------------- */

/* u = normalise(a + b - ((a + b) . e) e) (e unit or NULL). */
static void mean_direction(const double *a, const double *b, const double *e, double *u) {
  double s[3] = {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
  double p = e ? rn_dot3(s, e) : 0.0;
  for (int k = 0; k < 3; k++) s[k] -= e ? p * e[k] : 0.0;
  double n = sqrt(rn_dot3(s, s));
  for (int k = 0; k < 3; k++) u[k] = n > 0 ? s[k] / n : 0.0;
}

/* Current Voronoi length of interior vertex i of the polyline x. */
static double voronoi(const double *x, int i) {
  return 0.5 * (rn_dist3(&x[3 * i - 3], &x[3 * i]) + rn_dist3(&x[3 * i], &x[3 * i + 3]));
}

/* ---- point fields ------------------------------------------------------------ */

static rn_status fill_points(vtk_out *o, int rod, double *val) {
  return rn_network_rod_vertices(o->net, rod, val);
}

static rn_status fill_displacement(vtk_out *o, int rod, double *val) {
  int nv = rn_network_rod_num_vertices(o->net, rod);
  double *x0 = o->work[0];
  rn_status st = rn_network_rod_vertices(o->net, rod, val);
  if (!st) st = rn_network_rod_initial_vertices(o->net, rod, x0);
  for (int k = 0; !st && k < 3 * nv; k++) val[k] -= x0[k];
  return st;
}

/* Integrated curvature (ncomp 2) or twist (ncomp 1) per current Voronoi
 * length; 0 at the rod's ends. */
static rn_status strain_rate(vtk_out *o, int rod, int ncomp, double *val) {
  int nv = rn_network_rod_num_vertices(o->net, rod);
  double *x = o->work[0];
  const double *s = rod_strains(o, rod) + (ncomp == 2 ? 0 : 2 * (nv - 2));
  rn_status st = rn_network_rod_vertices(o->net, rod, x);
  if (st) return st;
  memset(val, 0, (size_t)(ncomp * nv) * sizeof *val);
  for (int i = 1; i + 1 < nv; i++)
    for (int k = 0; k < ncomp; k++)
      val[ncomp * i + k] = s[ncomp * (i - 1) + k] / voronoi(x, i);
  return RN_OK;
}

static rn_status fill_curvature(vtk_out *o, int rod, double *val) {
  return strain_rate(o, rod, 2, val);
}

static rn_status fill_twist_rate(vtk_out *o, int rod, double *val) {
  return strain_rate(o, rod, 1, val);
}

static rn_status fill_moment(vtk_out *o, int rod, double *val) {
  int nv = rn_network_rod_num_vertices(o->net, rod);
  const double *m = rod_vertex_fields(o, rod);
  memset(val, 0, (size_t)nv * sizeof *val);
  for (int i = 1; i + 1 < nv; i++) val[i] = hypot(m[2 * i - 2], m[2 * i - 1]);
  return RN_OK;
}

/* m1 e2 - m2 e1 with (e1, e2) the orthonormalised mean of the directors of
 * the vertex's two edges (the curvature binormal is kappa1 d2 - kappa2 d1). */
static rn_status fill_moment_vector(vtk_out *o, int rod, double *val) {
  int nv = rn_network_rod_num_vertices(o->net, rod);
  const double *m = rod_vertex_fields(o, rod);
  const double *d1 = rod_frames(o, rod), *d2 = d1 + 3 * (nv - 1);
  memset(val, 0, 3 * (size_t)nv * sizeof *val);
  for (int i = 1; i + 1 < nv; i++) {
    double e1[3], e2[3];
    mean_direction(&d1[3 * i - 3], &d1[3 * i], NULL, e1);
    mean_direction(&d2[3 * i - 3], &d2[3 * i], e1, e2);
    for (int k = 0; k < 3; k++)
      val[3 * i + k] = m[2 * i - 2] * e2[k] - m[2 * i - 1] * e1[k];
  }
  return RN_OK;
}

static rn_status fill_twisting_moment(vtk_out *o, int rod, double *val) {
  int nv = rn_network_rod_num_vertices(o->net, rod);
  memcpy(val + 1, rod_vertex_fields(o, rod) + 2 * (nv - 2),
         (size_t)(nv - 2) * sizeof *val);
  val[0] = val[nv - 1] = 0.0;
  return RN_OK;
}

/* ---- cell fields --------------------------------------------------------------- */

static rn_status fill_rod(vtk_out *o, int rod, double *val) {
  int ne = rn_network_rod_num_vertices(o->net, rod) - 1;
  for (int e = 0; e < ne; e++) val[e] = rod;
  return RN_OK;
}

static rn_status fill_edge(vtk_out *o, int rod, double *val) {
  int ne = rn_network_rod_num_vertices(o->net, rod) - 1;
  for (int e = 0; e < ne; e++) val[e] = e;
  return RN_OK;
}

static rn_status fill_theta(vtk_out *o, int rod, double *val) {
  return rn_network_rod_theta(o->net, rod, val);
}

static rn_status fill_stretch(vtk_out *o, int rod, double *val) {
  return rn_network_rod_strains(o->net, rod, val, NULL, NULL);
}

static rn_status fill_d1(vtk_out *o, int rod, double *val) {
  size_t n = 3 * (size_t)(rn_network_rod_num_vertices(o->net, rod) - 1);
  memcpy(val, rod_frames(o, rod), n * sizeof *val);
  return RN_OK;
}

static rn_status fill_d2(vtk_out *o, int rod, double *val) {
  size_t n = 3 * (size_t)(rn_network_rod_num_vertices(o->net, rod) - 1);
  memcpy(val, rod_frames(o, rod) + n, n * sizeof *val);
  return RN_OK;
}

/* Mean twist rate (as in twist_rate) of the edge's interior end vertices. */
static rn_status fill_edge_twist(vtk_out *o, int rod, double *val) {
  int nv = rn_network_rod_num_vertices(o->net, rod);
  double *rate = o->work[3];
  rn_status st = strain_rate(o, rod, 1, rate);
  if (st) return st;
  for (int e = 0; e + 1 < nv; e++) {
    int n = (e > 0) + (e + 2 < nv);
    val[e] = n ? (rate[e] + rate[e + 1]) / n : 0.0;
  }
  return RN_OK;
}

static rn_status fill_axial_force(vtk_out *o, int rod, double *val) {
  return rn_network_rod_edge_fields(o->net, rod, val, NULL);
}

/* rn_network_rod_internal_forces: the force and the moment (about the edge
 * midpoint) that the rest of the rod after the edge's midpoint exerts on the
 * part before it (cached for all rods). */
static rn_status fill_internal_force(vtk_out *o, int rod, double *val) {
  const size_t e = o->first[rod] + (size_t)rod,
               ne = o->first[rod + 1] + 1 - o->first[rod];
  memcpy(val, o->fi + 3 * e, 3 * ne * sizeof *val);
  return RN_OK;
}

static rn_status fill_internal_moment(vtk_out *o, int rod, double *val) {
  const size_t e = o->first[rod] + (size_t)rod,
               ne = o->first[rod + 1] + 1 - o->first[rod];
  memcpy(val, o->mi + 3 * e, 3 * ne * sizeof *val);
  return RN_OK;
}

static rn_status fill_rest_length(vtk_out *o, int rod, double *val) {
  return rn_network_rod_rest_lengths(o->net, rod, val);
}

/* Elastic energy per unit rest length of each edge: its stretching energy
 * plus, from each interior end vertex, the bending + twisting energy density
 * (energy / Voronoi rest length) over the half edge in that vertex's Voronoi
 * cell.  Sum over edges of energy_density * rest_length = elastic energy. */
static rn_status fill_energy_density(vtk_out *o, int rod, double *val) {
  int nv = rn_network_rod_num_vertices(o->net, rod);
  double *es = o->work[0], *len = o->work[3];
  const double *eb = rod_vertex_fields(o, rod) + 3 * (nv - 2), *et = eb + (nv - 2);
  rn_status st = rn_network_rod_edge_fields(o->net, rod, NULL, es);
  if (!st) st = rn_network_rod_rest_lengths(o->net, rod, len);
  if (st) return st;
  for (int e = 0; e + 1 < nv; e++) val[e] = es[e] / len[e];
  for (int i = 1; i + 1 < nv; i++) {
    double w = (eb[i - 1] + et[i - 1]) / (0.5 * (len[i - 1] + len[i]));
    val[i - 1] += 0.5 * w;
    val[i] += 0.5 * w;
  }
  return RN_OK;
}

/* ---- joints: one extra point and VTK_VERTEX cell each, after the rods ------ */

/* Rods' rows of the joint fields: no rotation (zeros), joint index -1. */
static rn_status fill_no_rotation(vtk_out *o, int rod, double *val) {
  memset(val, 0, 9 * (size_t)rn_network_rod_num_vertices(o->net, rod) * sizeof *val);
  return RN_OK;
}

static rn_status fill_no_joint(vtk_out *o, int rod, double *val) {
  int ne = rn_network_rod_num_vertices(o->net, rod) - 1;
  for (int e = 0; e < ne; e++) val[e] = -1;
  return RN_OK;
}

/* In the order of vtk.h.  Points come first: they are written in <Points>. */
static const vtk_field points_field = {"points", "Float64", 3, 0, fill_points};
static const vtk_field fields[] = {
    {"displacement", "Float64", 3, 0, fill_displacement},
    {"curvature", "Float64", 2, 0, fill_curvature},
    {"twist_rate", "Float64", 1, 0, fill_twist_rate},
    {"bending_moment", "Float64", 1, 0, fill_moment},
    {"bending_moment_vector", "Float64", 3, 0, fill_moment_vector},
    {"twisting_moment", "Float64", 1, 0, fill_twisting_moment},
    {"rod", "Int32", 1, 1, fill_rod},
    {"edge", "Int32", 1, 1, fill_edge},
    {"theta", "Float64", 1, 1, fill_theta},
    {"stretch", "Float64", 1, 1, fill_stretch},
    {"d1", "Float64", 3, 1, fill_d1},
    {"d2", "Float64", 3, 1, fill_d2},
    {"twist", "Float64", 1, 1, fill_edge_twist},
    {"axial_force", "Float64", 1, 1, fill_axial_force},
    {"internal_force", "Float64", 3, 1, fill_internal_force},
    {"internal_moment", "Float64", 3, 1, fill_internal_moment},
    {"rest_length", "Float64", 1, 1, fill_rest_length},
    {"energy_density", "Float64", 1, 1, fill_energy_density},
    {"joint_rotation", "Float64", 9, 0, fill_no_rotation},
    {"joint", "Int32", 1, 1, fill_no_joint},
};
enum { N_FIELDS = (int)(sizeof fields / sizeof fields[0]) };

/* ---- writing ------------------------------------------------------------------- */

/* Hands the buffered text to the file. */
static void out_flush(vtk_out *o) {
  if (o->len) fwrite(o->buf, 1, o->len, o->f);
  o->len = 0;
}

/* Room for n <= OUT_CAP more bytes at o->buf + o->len. */
static char *out_reserve(vtk_out *o, size_t n) {
  if (o->len + n > OUT_CAP) out_flush(o);
  return o->buf + o->len;
}

static void out_str(vtk_out *o, const char *s) {
  size_t n = strlen(s);
  memcpy(out_reserve(o, n), s, n);
  o->len += n;
}

/* Rows of up to 9 numbers. */
enum { ROW_MAX = 12 + 9 * RN_NUM_BUF };

static void put_rows(vtk_out *o, const double *v, int rows, int ncomp) {
  for (int r = 0; r < rows; r++) {
    char *row = out_reserve(o, ROW_MAX);
    size_t n = 10;
    memset(row, ' ', n);
    for (int k = 0; k < ncomp; k++) {
      double x = v[ncomp * r + k];
      if (!isfinite(x)) {
        if (!o->not_finite) {
          char field[128];
          if (o->rod >= 0)
            snprintf(field, sizeof field, "array \"%s\" of rod \"%s\"", o->array,
                     rn_network_rod_name(o->net, o->rod));
          else
            snprintf(field, sizeof field, "array \"%s\" of joint \"%s\"", o->array,
                     rn_network_joint_name(o->net, o->joint));
          rn_num_checked(&o->chk, field, x);
        }
        o->not_finite = 1;
        x = 0;
      }
      if (k) row[n++] = ' ';
      n += rn_format_g17(x, row + n);
    }
    row[n++] = '\n';
    o->len += n;
  }
}

/* One row "          a[ b]\n" of one or two integers (b < 0: none). */
static void put_ints(vtk_out *o, long a, long b) {
  char *row = out_reserve(o, 16 + 2 * RN_NUM_BUF);
  size_t n = 10;
  memset(row, ' ', n);
  n += rn_format_long(a, row + n);
  if (b >= 0) {
    row[n++] = ' ';
    n += rn_format_long(b, row + n);
  }
  row[n++] = '\n';
  o->len += n;
}

/* The row of joint j in field fld: position, displacement, rotation and
 * joint index; rod and edge -1; every other field 0. */
static rn_status joint_row(vtk_out *o, const vtk_field *fld, int j, double *val) {
  memset(val, 0, (size_t)fld->ncomp * sizeof *val);
  if (fld->fill == fill_points) return rn_network_joint_position(o->net, j, val);
  if (fld->fill == fill_no_rotation) return rn_network_joint_rotation(o->net, j, val);
  if (fld->fill == fill_no_joint) {
    val[0] = j;
  } else if (fld->fill == fill_rod || fld->fill == fill_edge) {
    val[0] = -1;
  } else if (fld->fill == fill_displacement) {
    double x0[3];
    rn_status st = rn_network_joint_position(o->net, j, val);
    if (!st) st = rn_scene_joint_initial_position(o->scene, j, x0);
    for (int k = 0; k < 3 && !st; k++) val[k] -= x0[k];
    return st;
  }
  return RN_OK;
}

static rn_status joint_rows(vtk_out *o, const vtk_field *fld) {
  int nj = rn_network_num_joints(o->net);
  rn_status st = RN_OK;
  for (int j = 0; j < nj && !st; j++) {
    st = joint_row(o, fld, j, o->val);
    o->rod = -1;
    o->joint = j;
    if (!st) put_rows(o, o->val, 1, fld->ncomp);
  }
  return st;
}

static rn_status data_array(vtk_out *o, const vtk_field *fld) {
  char head[256];
  snprintf(head, sizeof head,
           "        <DataArray type=\"%s\" Name=\"%s\" NumberOfComponents=\"%d\" "
           "format=\"ascii\">\n",
           fld->type, fld->name, fld->ncomp);
  out_str(o, head);
  rn_status st = RN_OK;
  int nrods = rn_network_num_rods(o->net);
  for (int r = 0; r < nrods && !st; r++) {
    int rows = rn_network_rod_num_vertices(o->net, r) - fld->on_edges;
    st = fld->fill(o, r, o->val);
    o->array = fld->name;
    o->rod = r;
    if (!st) put_rows(o, o->val, rows, fld->ncomp);
  }
  if (!st) st = joint_rows(o, fld);
  out_str(o, "        </DataArray>\n");
  return st;
}

static rn_status field_arrays(vtk_out *o, int on_edges) {
  rn_status st = RN_OK;
  for (int i = 0; i < N_FIELDS && !st; i++)
    if (fields[i].on_edges == on_edges) st = data_array(o, &fields[i]);
  return st;
}

static void cell_arrays(vtk_out *o) {
  int nrods = rn_network_num_rods(o->net);
  long base = 0, cells = 0;
  out_str(o,
          "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
  for (int r = 0; r < nrods; r++) {
    int nv = rn_network_rod_num_vertices(o->net, r);
    for (int e = 0; e + 1 < nv; e++) put_ints(o, base + e, base + e + 1);
    base += nv;
    cells += nv - 1;
  }
  int nj = rn_network_num_joints(o->net);
  for (int j = 0; j < nj; j++) put_ints(o, base + j, -1);
  out_str(o, "        </DataArray>\n"
             "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
  for (long c = 1; c <= cells; c++) put_ints(o, 2 * c, -1);
  for (int j = 1; j <= nj; j++) put_ints(o, 2 * cells + j, -1);
  out_str(o, "        </DataArray>\n"
             "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
  for (long c = 0; c < cells; c++) put_ints(o, VTK_LINE, -1);
  for (int j = 0; j < nj; j++) put_ints(o, VTK_VERTEX, -1);
  out_str(o, "        </DataArray>\n");
}

static rn_status write_body(vtk_out *o, long npoints, long ncells) {
  rn_status st;
  char head[512];
  snprintf(head, sizeof head,
           "<?xml version=\"1.0\"?>\n"
           "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
           "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
           "  <UnstructuredGrid>\n"
           "    <Piece NumberOfPoints=\"%ld\" NumberOfCells=\"%ld\">\n"
           "      <PointData Vectors=\"displacement\" Scalars=\"bending_moment\">\n",
           npoints, ncells);
  out_str(o, head);
  if ((st = field_arrays(o, 0))) return st;
  out_str(o, "      </PointData>\n      <CellData Scalars=\"energy_density\">\n");
  if ((st = field_arrays(o, 1))) return st;
  out_str(o, "      </CellData>\n      <Points>\n");
  if ((st = data_array(o, &points_field))) return st;
  out_str(o, "      </Points>\n      <Cells>\n");
  cell_arrays(o);
  out_str(o, "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
  out_flush(o);
  return RN_OK;
}

static rn_status write_vtu(FILE *f, void *user, rn_context *ctx) {
  vtk_out *o = user;
  int nrods = rn_network_num_rods(o->net), maxnv = 2;
  long npoints = 0, ncells = 0;
  for (int r = 0; r < nrods; r++) {
    int nv = rn_network_rod_num_vertices(o->net, r);
    if (nv > maxnv) maxnv = nv;
    npoints += nv;
    ncells += nv - 1;
  }
  npoints += rn_network_num_joints(o->net);
  ncells += rn_network_num_joints(o->net);
  o->f = f;
  /* val: 9 values per vertex (joint_rotation); work: 3 each */
  double *mem = malloc(3 * (size_t)maxnv * (N_WORK + 3) * sizeof *mem);
  o->buf = malloc(OUT_CAP);
  o->len = 0;
  o->val = mem;
  for (int k = 0; k < N_WORK; k++)
    o->work[k] = mem ? mem + 3 * (size_t)maxnv * (k + 3) : NULL;
  rn_status st = mem && o->buf ? cache_stencil_fields(o) : RN_ERR_ALLOC;
  if (!st) st = write_body(o, npoints, ncells);
  free(mem);
  free(o->buf);
  free(o->first);
  free(o->vf);
  free(o->kt);
  free(o->fr);
  free(o->fi);
  free(o->mi);
  if (st) {
    char msg[512];
    snprintf(msg, sizeof msg, "%s", rn_context_last_error(ctx));
    return rn_context_set_error(ctx, st, "VTK output: %s",
                                *msg ? msg : rn_status_message(st));
  }
  if (o->not_finite) {
    char msg[512];
    return rn_context_set_error(ctx, RN_ERR_NOT_FINITE, "VTK output %s",
                                rn_num_check_message(&o->chk, o->path, msg, sizeof msg));
  }
  return RN_OK;
}

rn_status rn_vtk_write(rn_context *ctx, const char *path, const rn_scene *scene) {
  vtk_out o;
  memset(&o, 0, sizeof o);
  o.scene = scene;
  o.net = rn_scene_network(scene);
  o.path = path;
  o.array = "Points";
  o.rod = -1;
  return rn_file_write_atomic(ctx, path, write_vtu, &o);
}
