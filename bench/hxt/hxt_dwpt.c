// hxt's 3D Delaunay (gmsh contrib/hxt/tetMesh, hxtDelaunay) on a .dwpt point
// file, timed like bench_scale_cgal: the construction from the points in
// memory, file reading and the copy into hxt's arrays not timed.
//
//   hxt_dwpt POINTS.dwpt [--threads N] [-o SIMPLICES.dwsx]
//
// Prints one JSON line: points, points hxt inserted, finite tetrahedra (hxt
// keeps ghost tetrahedra on the hull: counted apart), seconds of hxtDelaunay
// (bounding box, shuffle, Moore-curve sort, BRIO rounds, insertion, compaction).
// --threads N: hxt's delaunayThreads (0 = OMP_NUM_THREADS, the default).
// -o writes the finite tetrahedra as .dwsx (docs/formats.md) with the indices
// of the input file (hxt reorders its vertices; they are mapped back by their
// coordinates, untimed), for `dewall certify POINTS SIMPLICES --canonical`.
// Orientation is hxt's (certify accepts either).
//
// Links hxt's libraries from the user's gmsh checkout (bench/hxt/run.sh).
#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hxt_mesh.h"
#include "hxt_tetDelaunay.h"
#include "hxt_tools.h"

static void die(const char* what) {
  fprintf(stderr, "hxt_dwpt: %s\n", what);
  exit(1);
}

static const double* g_xyz;  // input coordinates, for the index map
static unsigned long g_warnings;  // hxt's warnings, counted instead of printed

// hxt warns once per repeated point it skips ("skipping supposedly duplicate
// point"); printed, 66,000 of them (kind indoor, 10^5 points) cost hxt's
// timed run their terminal output. Warnings are counted, everything else
// printed on stderr as hxt's default handler does.
static HXTStatus quiet_warnings(HXTMessage* msg) {
  if (msg->level == HXT_MSGLEVEL_WARNING) {
    g_warnings++;
    return HXT_STATUS_OK;
  }
  if (msg->level != HXT_MSGLEVEL_INFO) fprintf(stderr, "hxt: %s\n", msg->string);
  return HXT_STATUS_OK;
}

static int cmp_xyz(const void* a, const void* b) {
  const double* p = g_xyz + 3 * (size_t)*(const uint32_t*)a;
  const double* q = g_xyz + 3 * (size_t)*(const uint32_t*)b;
  for (int k = 0; k < 3; k++) {
    if (p[k] < q[k]) return -1;
    if (p[k] > q[k]) return 1;
  }
  // Equal points (repeats in the input): the first occurrence first, so that a
  // vertex maps to it, as `dewall certify` expects.
  const uint32_t i = *(const uint32_t*)a, j = *(const uint32_t*)b;
  return i < j ? -1 : i > j;
}

// Index in the input of the point with coordinates c (sorted = input indices by coordinates).
static uint32_t original_index(const uint32_t* sorted, uint32_t n, const double* c) {
  uint32_t lo = 0, hi = n;
  while (lo < hi) {
    uint32_t mid = lo + (hi - lo) / 2;
    const double* p = g_xyz + 3 * (size_t)sorted[mid];
    int less = p[0] < c[0] || (p[0] == c[0] && (p[1] < c[1] || (p[1] == c[1] && p[2] < c[2])));
    if (less) lo = mid + 1; else hi = mid;
  }
  if (lo == n || memcmp(g_xyz + 3 * (size_t)sorted[lo], c, 3 * sizeof(double)) != 0) die("vertex not found in the input");
  return sorted[lo];
}

int main(int argc, char** argv) {
  const char* input = NULL;
  const char* output = NULL;
  int threads = 0;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--threads") && i + 1 < argc) threads = atoi(argv[++i]);
    else if (!strcmp(argv[i], "-o") && i + 1 < argc) output = argv[++i];
    else if (!input && argv[i][0] != '-') input = argv[i];
    else die("usage: hxt_dwpt POINTS.dwpt [--threads N] [-o SIMPLICES.dwsx]");
  }
  if (!input) die("usage: hxt_dwpt POINTS.dwpt [--threads N] [-o SIMPLICES.dwsx]");

  // .dwpt: 'DWPT', version 1, dimension, flags 0, count (u64), then doubles.
  FILE* f = fopen(input, "rb");
  if (!f) die("cannot open the input");
  unsigned char h[24];
  if (fread(h, 1, 24, f) != 24 || memcmp(h, "DWPT", 4) != 0) die("not a .dwpt file");
  uint32_t version, dim, flags;
  uint64_t count;
  memcpy(&version, h + 4, 4);
  memcpy(&dim, h + 8, 4);
  memcpy(&flags, h + 12, 4);
  memcpy(&count, h + 16, 8);
  if (version != 1 || flags != 0 || dim != 3) die("need a version 1, 3D .dwpt file");
  if (count < 5 || count >= UINT32_MAX) die("need 5 to 2^32-2 points");
  const uint32_t n = (uint32_t)count;
  double* xyz = malloc(sizeof(double) * 3 * (size_t)n);
  if (!xyz || fread(xyz, sizeof(double), 3 * (size_t)n, f) != 3 * (size_t)n) die("truncated file");
  fclose(f);

  hxtSetMessageCallback(quiet_warnings);
  HXTMesh* mesh;
  if (hxtMeshCreate(&mesh) != HXT_STATUS_OK) die("hxtMeshCreate");
  if (hxtAlignedMalloc(&mesh->vertices.coord, sizeof(double) * 4 * (size_t)n) != HXT_STATUS_OK) die("out of memory");
  for (uint32_t i = 0; i < n; i++) {
    memcpy(mesh->vertices.coord + 4 * (size_t)i, xyz + 3 * (size_t)i, 3 * sizeof(double));
    mesh->vertices.coord[4 * (size_t)i + 3] = 0.0;
  }
  mesh->vertices.num = mesh->vertices.size = n;

  HXTDelaunayOptions opt = {0};
  opt.perfectDelaunay = 1;  // as Delaunay_CLI: no constraints
  opt.delaunayThreads = threads;
  opt.verbosity = 0;

  const double t0 = omp_get_wtime();
  if (hxtDelaunay(mesh, &opt) != HXT_STATUS_OK) die("hxtDelaunay failed");
  const double seconds = omp_get_wtime() - t0;

  uint64_t finite = 0, ghost = 0;
  for (uint64_t t = 0; t < mesh->tetrahedra.num; t++) {
    const uint32_t* v = mesh->tetrahedra.node + 4 * t;
    if (v[0] == HXT_GHOST_VERTEX || v[1] == HXT_GHOST_VERTEX || v[2] == HXT_GHOST_VERTEX || v[3] == HXT_GHOST_VERTEX)
      ghost++;
    else
      finite++;
  }
  printf("{\"tool\": \"hxt\", \"threads\": %d, \"points\": %u, \"inserted\": %u, \"cells\": %llu, \"ghost_cells\": %llu, "
         "\"warnings\": %lu, \"seconds\": %.3f}\n",
         opt.delaunayThreads, n, mesh->vertices.num, (unsigned long long)finite, (unsigned long long)ghost, g_warnings,
         seconds);
  fflush(stdout);

  if (output) {
    uint32_t* sorted = malloc(sizeof(uint32_t) * (size_t)n);
    uint32_t* map = malloc(sizeof(uint32_t) * (size_t)mesh->vertices.num);
    if (!sorted || !map) die("out of memory");
    for (uint32_t i = 0; i < n; i++) sorted[i] = i;
    g_xyz = xyz;
    qsort(sorted, n, sizeof(uint32_t), cmp_xyz);
    for (uint32_t i = 0; i < mesh->vertices.num; i++)
      map[i] = original_index(sorted, n, mesh->vertices.coord + 4 * (size_t)i);
    FILE* o = fopen(output, "wb");
    if (!o) die("cannot open the output");
    const uint32_t hdr[4] = {0x58535744u /* "DWSX" */, 1, 3, 4};
    fwrite(hdr, 4, 4, o);
    fwrite(&finite, 8, 1, o);
    for (uint64_t t = 0; t < mesh->tetrahedra.num; t++) {
      const uint32_t* v = mesh->tetrahedra.node + 4 * t;
      if (v[0] == HXT_GHOST_VERTEX || v[1] == HXT_GHOST_VERTEX || v[2] == HXT_GHOST_VERTEX || v[3] == HXT_GHOST_VERTEX)
        continue;
      const uint32_t s[4] = {map[v[0]], map[v[1]], map[v[2]], map[v[3]]};
      fwrite(s, 4, 4, o);
    }
    if (fclose(o) != 0) die("write failed");
    free(sorted);
    free(map);
  }
  hxtMeshDelete(&mesh);
  free(xyz);
  return 0;
}
