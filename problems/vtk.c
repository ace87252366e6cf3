/* vtk.c - .vtu writer (VTK XML UnstructuredGrid, ASCII). */
#include "vtk.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "atomic_file.h"

enum { VTK_LINE = 3 };

/* Per-rod quantities written as one data array over all rods. */
typedef enum vtk_field {
  F_POINTS,
  F_DISPLACEMENT,
  F_CURVATURE,
  F_TWIST_RATE, /* per vertex */
  F_ROD,
  F_EDGE,
  F_THETA,
  F_STRETCH,
  F_D1,
  F_D2 /* per edge */
} vtk_field;

typedef struct vtk_out {
  FILE *f;
  rn_network *net;
  int not_finite;
  double *a, *b; /* scratch, 3 * max vertices each */
} vtk_out;

static void put_num(vtk_out *o, double x) {
  if (!isfinite(x)) {
    o->not_finite = 1;
    x = 0;
  }
  fprintf(o->f, "%.17g", x);
}

static void put_row(vtk_out *o, const double *v, int n) {
  fputs("          ", o->f);
  for (int k = 0; k < n; k++) {
    if (k) fputc(' ', o->f);
    put_num(o, v[k]);
  }
  fputc('\n', o->f);
}

static double dist3(const double *p, const double *q) {
  double d[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
  return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

/* Per-vertex rows of one rod: points, displacement, curvature, twist rate. */
static rn_status vertex_rows(vtk_out *o, int rod, vtk_field fld) {
  int nv = rn_network_rod_num_vertices(o->net, rod);
  double *x = o->a, *y = o->b;
  rn_status st = rn_network_rod_vertices(o->net, rod, x);
  if (!st && fld == F_DISPLACEMENT) st = rn_network_rod_initial_vertices(o->net, rod, y);
  if (!st && fld == F_CURVATURE) st = rn_network_rod_strains(o->net, rod, NULL, y, NULL);
  if (!st && fld == F_TWIST_RATE) st = rn_network_rod_strains(o->net, rod, NULL, NULL, y);
  if (st) return st;
  for (int i = 0; i < nv; i++) {
    const double *p = &x[3 * i];
    double row[3] = {0, 0, 0};
    int interior = i > 0 && i + 1 < nv;
    double vor = interior ? 0.5 * (dist3(p - 3, p) + dist3(p, p + 3)) : 1;
    switch (fld) {
    case F_POINTS:
      put_row(o, p, 3);
      break;
    case F_DISPLACEMENT:
      for (int k = 0; k < 3; k++) row[k] = p[k] - y[3 * i + k];
      put_row(o, row, 3);
      break;
    case F_CURVATURE:
      if (interior) {
        row[0] = y[2 * (i - 1)] / vor;
        row[1] = y[2 * (i - 1) + 1] / vor;
      }
      put_row(o, row, 2);
      break;
    default:
      if (interior) row[0] = y[i - 1] / vor;
      put_row(o, row, 1);
      break;
    }
  }
  return RN_OK;
}

/* Per-edge rows of one rod. */
static rn_status edge_rows(vtk_out *o, int rod, vtk_field fld) {
  int ne = rn_network_rod_num_vertices(o->net, rod) - 1;
  double *y = o->a;
  rn_status st = RN_OK;
  if (fld == F_THETA)
    st = rn_network_rod_theta(o->net, rod, y);
  else if (fld == F_STRETCH)
    st = rn_network_rod_strains(o->net, rod, y, NULL, NULL);
  else if (fld == F_D1)
    st = rn_network_rod_frames(o->net, rod, y, NULL);
  else if (fld == F_D2)
    st = rn_network_rod_frames(o->net, rod, NULL, y);
  if (st) return st;
  for (int e = 0; e < ne; e++) {
    if (fld == F_ROD || fld == F_EDGE)
      fprintf(o->f, "          %d\n", fld == F_ROD ? rod : e);
    else if (fld == F_D1 || fld == F_D2)
      put_row(o, &y[3 * e], 3);
    else
      put_row(o, &y[e], 1);
  }
  return RN_OK;
}

static rn_status data_array(vtk_out *o, vtk_field fld, const char *name, const char *type,
                            int ncomp) {
  fprintf(o->f,
          "        <DataArray type=\"%s\"%s%s%s NumberOfComponents=\"%d\" "
          "format=\"ascii\">\n",
          type, name ? " Name=\"" : "", name ? name : "", name ? "\"" : "", ncomp);
  rn_status st = RN_OK;
  int nrods = rn_network_num_rods(o->net);
  for (int r = 0; r < nrods && !st; r++)
    st = fld <= F_TWIST_RATE ? vertex_rows(o, r, fld) : edge_rows(o, r, fld);
  fputs("        </DataArray>\n", o->f);
  return st;
}

static void cell_arrays(vtk_out *o) {
  FILE *f = o->f;
  int nrods = rn_network_num_rods(o->net);
  long base = 0, cells = 0;
  fputs("        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n", f);
  for (int r = 0; r < nrods; r++) {
    int nv = rn_network_rod_num_vertices(o->net, r);
    for (int e = 0; e + 1 < nv; e++)
      fprintf(f, "          %ld %ld\n", base + e, base + e + 1);
    base += nv;
    cells += nv - 1;
  }
  fputs("        </DataArray>\n"
        "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n",
        f);
  for (long c = 1; c <= cells; c++) fprintf(f, "          %ld\n", 2 * c);
  fputs("        </DataArray>\n"
        "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n",
        f);
  for (long c = 0; c < cells; c++) fprintf(f, "          %d\n", VTK_LINE);
  fputs("        </DataArray>\n", f);
}

static rn_status write_body(vtk_out *o, long npoints, long ncells) {
  FILE *f = o->f;
  rn_status st;
  fprintf(f,
          "<?xml version=\"1.0\"?>\n"
          "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
          "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
          "  <UnstructuredGrid>\n"
          "    <Piece NumberOfPoints=\"%ld\" NumberOfCells=\"%ld\">\n"
          "      <PointData Vectors=\"displacement\">\n",
          npoints, ncells);
  if ((st = data_array(o, F_DISPLACEMENT, "displacement", "Float64", 3))) return st;
  if ((st = data_array(o, F_CURVATURE, "curvature", "Float64", 2))) return st;
  if ((st = data_array(o, F_TWIST_RATE, "twist_rate", "Float64", 1))) return st;
  fputs("      </PointData>\n      <CellData Scalars=\"theta\">\n", f);
  if ((st = data_array(o, F_ROD, "rod", "Int32", 1))) return st;
  if ((st = data_array(o, F_EDGE, "edge", "Int32", 1))) return st;
  if ((st = data_array(o, F_THETA, "theta", "Float64", 1))) return st;
  if ((st = data_array(o, F_STRETCH, "stretch", "Float64", 1))) return st;
  if ((st = data_array(o, F_D1, "d1", "Float64", 3))) return st;
  if ((st = data_array(o, F_D2, "d2", "Float64", 3))) return st;
  fputs("      </CellData>\n      <Points>\n", f);
  if ((st = data_array(o, F_POINTS, "points", "Float64", 3))) return st;
  fputs("      </Points>\n      <Cells>\n", f);
  cell_arrays(o);
  fputs("      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n", f);
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
  o->f = f;
  o->a = malloc(3 * (size_t)maxnv * sizeof *o->a);
  o->b = malloc(3 * (size_t)maxnv * sizeof *o->b);
  rn_status st = (o->a && o->b) ? write_body(o, npoints, ncells) : RN_ERR_ALLOC;
  free(o->a);
  free(o->b);
  if (st) {
    char msg[512];
    snprintf(msg, sizeof msg, "%s", rn_context_last_error(ctx));
    return rn_context_set_error(ctx, st, "VTK output: %s",
                                *msg ? msg : rn_status_message(st));
  }
  if (o->not_finite)
    return rn_context_set_error(ctx, RN_ERR_NOT_FINITE,
                                "VTK output: the result contains "
                                "NaN or infinite values; no file written");
  return RN_OK;
}

rn_status rn_vtk_write(rn_context *ctx, const char *path, const rn_scene *scene) {
  vtk_out o = {NULL, rn_scene_network(scene), 0, NULL, NULL};
  return rn_file_write_atomic(ctx, path, write_vtu, &o);
}
