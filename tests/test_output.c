/* test_output.c - the output contract (output.c, results.c): every file read back and compared,
 * stale files, atomicity under I/O errors and injected allocation failures. (The directory
 * itself - creation on commit, the lock, stale staging areas, interruption - is test_outdir.c.)
 * Each test removes its temporary directory when it passes. */
#include <check.h>
#include <dirent.h>
#include <jansson.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/alloc.h"
#include "kernels/kernel.h"
#include "io/npy.h"
#include "pipeline/output.h"
#include "pipeline/results.h"
#include "test_util.h"

enum { NX = 12, NY = 7, NL = 4, IMAX = 5, JMAX = 3 };

static double *field(size_t n, unsigned long long seed)
{
    double *f = mc_zeros(n);
    ck_assert(f != NULL);
    test_random_field(f, n, seed);
    return f;
}

static void make_results(mc_results *r, int with_stress)
{
    memset(r, 0, sizeof *r);
    mc_grid g = {NX, NY, 1e-6, 1.5e-6, 1, 0};
    r->grid = g;
    size_t n = NX * NY;
    r->topography = field(n, 1);
    r->pressure = field(n, 2);
    r->gap = field(n, 3);
    r->displacement = field(n, 4);
    r->pressure[JMAX * NX + IMAX] = 5.0; /* the unique maximum (random values are < 1) */
    mc_contact_summary c = {1, 12.5, 11.0, 5.0, 3.25e-11, 0.125, 1.5e-7, 17, 3e-9, 1, "cg",
                            MC_BACKEND_DIRECT, 2};
    r->contact = c;
    r->timing.total_s = 1.5;
    r->timing.setup_s = 0.25;
    r->timing.contact_s = 0.75;
    r->timing.stress_s = with_stress ? 0.5 : 0.0;
    r->roughness_seed = 123456789ULL;
    if (!with_stress)
        return;
    r->nlayers = NL;
    r->depths = mc_zeros(NL);
    for (int k = 0; k < NL; k++)
        r->depths[k] = 0.5e-6 * (k + 1);
    for (int s = 0; s < MC_NSTRESS; s++)
        r->stress[s] = field(n * NL, 10 + (unsigned long long)s);
    r->von_mises = field(n * NL, 20);
    r->hydrostatic = field(n * NL, 21);
    r->tresca = field(n * NL, 22);
    mc_stage_stress_summary ss = {2.5e9, {1e-6, -2e-6, 3e-7}, -1e9, 1.25e9, {0, 0, 4e-7}, NL, 0.5e-6,
                            2e-6, "patch", 0.1};
    r->stress_summary = ss;
}

static void make_scene(mc_scene *s, int vtk)
{
    memset(s, 0, sizeof *s);
    snprintf(s->path, sizeof s->path, "cases/example.ini");
    s->geometry.shape = MC_SHAPE_SPHERE;
    s->geometry.radius = 0.01;
    s->roughness.type = MC_ROUGH_GAUSSIAN;
    s->roughness.rq = 0.4e-6;
    s->roughness.correlation_x = 5e-6;
    s->roughness.correlation_y = 50e-6;
    s->roughness.seed = 123456789ULL;
    s->body1.E = s->body2.E = 210e9;
    s->body1.nu = s->body2.nu = 0.3;
    s->load.kind = MC_LOAD_FORCE;
    s->load.value = 12.5;
    s->load.pressure_cap = INFINITY;
    s->solver.tolerance = 1e-8;
    s->solver.max_iterations = 1000;
    s->output.vtk = vtk;
}

static char *path_in(const char *dir, const char *name)
{
    static char p[8][1024];
    static int k;
    k = (k + 1) % 8;
    snprintf(p[k], sizeof p[k], "%s/%s", dir, name);
    return p[k];
}

static int exists(const char *dir, const char *name)
{
    return access(path_in(dir, name), F_OK) == 0;
}

/* Sorted names in dir (without . and ..), one per line; malloc'ed. */
static char *listing(const char *dir)
{
    struct dirent **e;
    int n = scandir(dir, &e, NULL, alphasort);
    ck_assert_int_ge(n, 0);
    char *out = calloc(1, 8192);
    for (int k = 0; k < n; k++) {
        if (strcmp(e[k]->d_name, ".") && strcmp(e[k]->d_name, "..")) {
            strcat(out, e[k]->d_name);
            strcat(out, "\n");
        }
        free(e[k]);
    }
    free(e);
    return out;
}

/* Listing plus an FNV-1a hash of every file's bytes: any change to DIR shows. */
static char *snapshot(const char *dir)
{
    char *names = listing(dir), *out = calloc(1, 16384), *save = NULL;
    for (char *nm = strtok_r(names, "\n", &save); nm; nm = strtok_r(NULL, "\n", &save)) {
        uint64_t h = 1469598103934665603ULL;
        FILE *f = fopen(path_in(dir, nm), "rb");
        if (f) {
            int ch;
            while ((ch = fgetc(f)) != EOF)
                h = (h ^ (uint64_t)ch) * 1099511628211ULL;
            fclose(f);
        }
        char line[300];
        snprintf(line, sizeof line, "%s %016llx\n", nm, (unsigned long long)h);
        strcat(out, line);
    }
    free(names);
    return out;
}

static void check_npy2(const char *dir, const char *name, const double *want)
{
    double *d;
    int r, c;
    mc_error err = {0};
    ck_assert_msg(mc_npy_read(path_in(dir, name), &d, &r, &c, &err) == MC_OK, "%s", err.msg);
    ck_assert_int_eq(r, NY);
    ck_assert_int_eq(c, NX);
    ck_assert_mem_eq(d, want, sizeof(double) * NX * NY);
    mc_free(d);
}

/* mc_npy_read accepts rank <= 2 only: check a volume's header and bytes directly. */
static void check_npy3(const char *dir, const char *name, const double *want)
{
    unsigned char *b;
    size_t len;
    mc_error err = {0};
    ck_assert_int_eq(mc_io_read_file(path_in(dir, name), &b, &len, &err), MC_OK);
    size_t hlen = b[8] | (size_t)b[9] << 8, n = (size_t)NL * NY * NX;
    char dict[128];
    snprintf(dict, sizeof dict, "{'descr': '<f8', 'fortran_order': False, 'shape': (%d, %d, %d), }",
             NL, NY, NX);
    ck_assert_mem_eq(b + 10, dict, strlen(dict));
    ck_assert_uint_eq((10 + hlen) % 64, 0);
    ck_assert_uint_eq(len, 10 + hlen + 8 * n);
    ck_assert_mem_eq(b + 10 + hlen, want, 8 * n);
    mc_free(b);
}

/* Lines of a small CSV file; *nlines set; malloc'ed array of malloc'ed strings. */
static char **read_lines(const char *path, int *nlines)
{
    FILE *f = fopen(path, "r");
    ck_assert_msg(f != NULL, "%s", path);
    char **lines = calloc(256, sizeof *lines), buf[4096];
    int n = 0;
    while (fgets(buf, sizeof buf, f)) {
        ck_assert_int_lt(n, 256);
        buf[strcspn(buf, "\n")] = '\0';
        lines[n++] = strdup(buf);
    }
    fclose(f);
    *nlines = n;
    return lines;
}

static void free_lines(char **l, int n)
{
    for (int k = 0; k < n; k++)
        free(l[k]);
    free(l);
}

/* Parse "a,b,c" into v (exact %.17g round trip); returns the count. */
static int csv_values(const char *line, double *v, int max)
{
    int n = 0;
    const char *p = line;
    while (*p && n < max) {
        char *end;
        v[n++] = strtod(p, &end);
        ck_assert_ptr_ne(end, p);
        p = *end == ',' ? end + 1 : end;
    }
    return n;
}

static void check_csv(const char *dir, const mc_results *r)
{
    int n;
    double v[16];
    char **l = read_lines(path_in(dir, "profile_x.csv"), &n);
    ck_assert_str_eq(l[0], "x,pressure,gap,displacement");
    ck_assert_int_eq(n, NX + 1);
    for (int i = 0; i < NX; i++) {
        ck_assert_int_eq(csv_values(l[i + 1], v, 16), 4);
        size_t k = JMAX * NX + i;
        ck_assert_double_eq(v[0], mc_grid_x(&r->grid, i));
        ck_assert_double_eq(v[1], r->pressure[k]);
        ck_assert_double_eq(v[2], r->gap[k]);
        ck_assert_double_eq(v[3], r->displacement[k]);
    }
    free_lines(l, n);
    if (r->nlayers == 0)
        return;
    l = read_lines(path_in(dir, "depths.csv"), &n);
    ck_assert_str_eq(l[0], "layer,z");
    ck_assert_int_eq(n, NL + 1);
    for (int k = 0; k < NL; k++) {
        ck_assert_int_eq(csv_values(l[k + 1], v, 16), 2);
        ck_assert_double_eq(v[0], k);
        ck_assert_double_eq(v[1], r->depths[k]);
    }
    free_lines(l, n);
    l = read_lines(path_in(dir, "axis.csv"), &n);
    ck_assert_str_eq(l[0], "z,sxx,syy,szz,sxy,syz,sxz,von_mises,hydrostatic,tresca");
    ck_assert_int_eq(n, NL + 1);
    for (int k = 0; k < NL; k++) {
        size_t q = (size_t)k * NX * NY + JMAX * NX + IMAX;
        ck_assert_int_eq(csv_values(l[k + 1], v, 16), 10);
        ck_assert_double_eq(v[0], r->depths[k]);
        for (int s = 0; s < MC_NSTRESS; s++)
            ck_assert_double_eq(v[1 + s], r->stress[s][q]);
        ck_assert_double_eq(v[7], r->von_mises[q]);
        ck_assert_double_eq(v[8], r->hydrostatic[q]);
        ck_assert_double_eq(v[9], r->tresca[q]);
    }
    free_lines(l, n);
}

static double jreal(json_t *o, const char *key)
{
    json_t *v = json_object_get(o, key);
    ck_assert_msg(v != NULL && json_is_number(v), "key %s", key);
    return json_number_value(v);
}

static json_t *jobj(json_t *o, const char *key)
{
    json_t *v = json_object_get(o, key);
    ck_assert_msg(v != NULL && json_is_object(v), "object %s", key);
    return v;
}

static void check_summary(const char *dir, const mc_scene *s, const mc_results *r)
{
    json_error_t je;
    json_t *root = json_load_file(path_in(dir, "summary.json"), 0, &je);
    ck_assert_msg(root != NULL, "summary.json: %s (line %d)", je.text, je.line);
    ck_assert_str_eq(json_string_value(json_object_get(root, "case")), s->path);
    ck_assert_int_eq((int)jreal(root, "format_version"), 1);

    json_t *m = jobj(root, "mesh");
    ck_assert_int_eq((int)jreal(m, "nx"), NX);
    ck_assert_int_eq((int)jreal(m, "ny"), NY);
    ck_assert_double_eq(jreal(m, "dx"), r->grid.dx);
    ck_assert_double_eq(jreal(m, "dy"), r->grid.dy);
    ck_assert(json_is_true(json_object_get(m, "periodic_x")));
    ck_assert(json_is_false(json_object_get(m, "periodic_y")));

    json_t *mat = jobj(root, "materials");
    ck_assert_double_eq(jreal(jobj(mat, "body1"), "E"), 210e9);
    ck_assert_double_eq(jreal(jobj(mat, "body2"), "nu"), 0.3);
    ck_assert_double_eq_tol(jreal(mat, "estar"), 210e9 / (2 * (1 - 0.09)), 1e-3);

    json_t *ld = jobj(root, "load");
    ck_assert_str_eq(json_string_value(json_object_get(ld, "kind")), "force");
    ck_assert_double_eq(jreal(ld, "value"), 12.5);
    ck_assert_double_eq(jreal(ld, "lubricant_pressure"), 0.0);
    ck_assert(json_is_null(json_object_get(ld, "pressure_cap"))); /* +inf */

    json_t *ro = jobj(root, "roughness");
    ck_assert_str_eq(json_string_value(json_object_get(ro, "type")), "gaussian");
    ck_assert_int_eq(json_integer_value(json_object_get(ro, "seed")), 123456789);
    ck_assert_double_eq(jreal(ro, "rq"), 0.4e-6);
    ck_assert_double_eq(jreal(ro, "correlation_y"), 50e-6);

    json_t *c = jobj(root, "contact");
    ck_assert_double_eq(jreal(c, "load"), 12.5);
    ck_assert_double_eq(jreal(c, "solid_load"), 11.0);
    ck_assert_double_eq(jreal(c, "p_max"), 5.0);
    ck_assert_double_eq(jreal(c, "area"), 3.25e-11);
    ck_assert_double_eq(jreal(c, "contact_ratio"), 0.125);
    ck_assert_double_eq(jreal(c, "approach"), 1.5e-7); /* 17 digits: exact round trip */
    ck_assert_int_eq((int)jreal(c, "iterations"), 17);
    ck_assert_double_eq(jreal(c, "residual"), 3e-9);
    ck_assert(json_is_true(json_object_get(c, "converged")));
    ck_assert(json_is_true(json_object_get(c, "solved")));
    ck_assert_str_eq(json_string_value(json_object_get(c, "state")), "converged");
    ck_assert_str_eq(json_string_value(json_object_get(c, "solver")), "cg");
    ck_assert_str_eq(json_string_value(json_object_get(c, "operator")), "direct");
    ck_assert_int_eq((int)jreal(c, "capped_cells"), 2);

    json_t *st = json_object_get(root, "stress");
    if (r->nlayers > 0) {
        ck_assert(json_is_object(st));
        ck_assert_double_eq(jreal(st, "vm_max"), 2.5e9);
        json_t *at = json_object_get(st, "vm_max_at");
        ck_assert_int_eq(json_array_size(at), 3);
        ck_assert_double_eq(json_number_value(json_array_get(at, 1)), -2e-6);
        ck_assert_double_eq(jreal(st, "hydro_at_vm_max"), -1e9);
        ck_assert_double_eq(jreal(st, "tresca_max"), 1.25e9);
        json_t *tat = json_object_get(st, "tresca_max_at");
        ck_assert_double_eq(json_number_value(json_array_get(tat, 2)), 4e-7);
        ck_assert_int_eq((int)jreal(st, "layers"), NL);
        ck_assert_double_eq(jreal(st, "depth_min"), 0.5e-6);
        ck_assert_double_eq(jreal(st, "depth_max"), 2e-6);
        ck_assert_str_eq(json_string_value(json_object_get(st, "kernel")), "patch");
        ck_assert_double_eq(jreal(st, "friction"), 0.1);
    } else {
        ck_assert_ptr_null(st);
    }
    json_t *t = jobj(root, "timing");
    ck_assert_double_eq(jreal(t, "total_s"), 1.5);
    ck_assert_double_eq(jreal(t, "setup_s"), 0.25);
    ck_assert_double_eq(jreal(t, "contact_s"), 0.75);
    ck_assert_double_eq(jreal(t, "stress_s"), r->timing.stress_s);

    /* "files" names exactly what DIR holds: nothing more (no staging, no stale files) */
    json_t *files = json_object_get(root, "files");
    ck_assert(json_is_array(files));
    char *want = listing(dir), got[8192] = "";
    const char *names[64];
    size_t nf = json_array_size(files);
    ck_assert_uint_lt(nf, 64);
    for (size_t k = 0; k < nf; k++)
        names[k] = json_string_value(json_array_get(files, k));
    for (size_t a = 0; a < nf; a++)
        for (size_t b = a + 1; b < nf; b++)
            if (strcmp(names[a], names[b]) > 0) {
                const char *tmp = names[a];
                names[a] = names[b];
                names[b] = tmp;
            }
    for (size_t k = 0; k < nf; k++) {
        strcat(got, names[k]);
        strcat(got, "\n");
    }
    ck_assert_str_eq(got, want);
    free(want);
    json_decref(root);
}

/* Appended raw VTK data: the block at each declared offset is a UInt64 byte count plus the
 * array's little-endian bytes. */
static const unsigned char *vtk_block(const unsigned char *b, size_t len, const char *name,
                                      uint64_t *nbytes)
{
    char key[64];
    snprintf(key, sizeof key, "Name=\"%s\" format=\"appended\" offset=\"", name);
    const char *p = strstr((const char *)b, key);
    ck_assert_msg(p != NULL, "array %s", name);
    unsigned long long off = strtoull(p + strlen(key), NULL, 10);
    const char *app = strstr((const char *)b, "<AppendedData encoding=\"raw\">");
    ck_assert(app != NULL);
    const unsigned char *base = (const unsigned char *)strchr(app, '_') + 1;
    ck_assert((size_t)(base - b) + off + 8 <= len);
    memcpy(nbytes, base + off, 8);
    ck_assert((size_t)(base - b) + off + 8 + *nbytes <= len);
    return base + off + 8;
}

/* The k-th double of an unaligned little-endian block. */
static double dbl_at(const unsigned char *p, size_t k)
{
    double v;
    memcpy(&v, p + 8 * k, sizeof v);
    return v;
}

static void check_vtk(const char *dir, const mc_results *r)
{
    unsigned char *b;
    size_t len;
    uint64_t nb;
    mc_error err = {0};
    ck_assert_int_eq(mc_io_read_file(path_in(dir, "field.vti"), &b, &len, &err), MC_OK);
    ck_assert(strstr((char *)b, "type=\"ImageData\"") &&
              strstr((char *)b, "header_type=\"UInt64\""));
    char ext[128];
    snprintf(ext, sizeof ext, "WholeExtent=\"0 %d 0 %d 0 0\"", NX, NY);
    ck_assert(strstr((char *)b, ext) != NULL);
    char spacing[128];
    snprintf(spacing, sizeof spacing, "Spacing=\"%.17g %.17g ", r->grid.dx, r->grid.dy);
    ck_assert_msg(strstr((char *)b, spacing) != NULL, "%s", spacing);
    ck_assert(strstr((char *)b, "<CellData"));
    const char *names[4] = {"pressure", "gap", "displacement", "topography"};
    const double *arr[4] = {r->pressure, r->gap, r->displacement, r->topography};
    for (int a = 0; a < 4; a++) {
        const unsigned char *d = vtk_block(b, len, names[a], &nb);
        ck_assert_uint_eq(nb, 8 * NX * NY);
        ck_assert_mem_eq(d, arr[a], nb);
    }
    ck_assert(strstr((char *)b + len - 40, "</AppendedData>\n</VTKFile>\n"));
    mc_free(b);
    if (r->nlayers == 0) {
        ck_assert(!exists(dir, "stress.vtr"));
        return;
    }
    ck_assert_int_eq(mc_io_read_file(path_in(dir, "stress.vtr"), &b, &len, &err), MC_OK);
    ck_assert(strstr((char *)b, "type=\"RectilinearGrid\"") && strstr((char *)b, "<PointData"));
    snprintf(ext, sizeof ext, "WholeExtent=\"0 %d 0 %d 0 %d\"", NX - 1, NY - 1, NL - 1);
    ck_assert(strstr((char *)b, ext) != NULL);
    const unsigned char *z = vtk_block(b, len, "z", &nb);
    ck_assert_uint_eq(nb, 8 * NL);
    for (int k = 0; k < NL; k++) /* deepest first: z = -depth increasing */
        ck_assert_double_eq(dbl_at(z, (size_t)k), -r->depths[NL - 1 - k]);
    const unsigned char *x = vtk_block(b, len, "x", &nb);
    ck_assert_uint_eq(nb, 8 * NX);
    for (int i = 0; i < NX; i++)
        ck_assert_double_eq(dbl_at(x, (size_t)i), mc_grid_x(&r->grid, i));
    const unsigned char *y = vtk_block(b, len, "y", &nb);
    ck_assert_uint_eq(nb, 8 * NY);
    for (int j = 0; j < NY; j++)
        ck_assert_double_eq(dbl_at(y, (size_t)j), mc_grid_y(&r->grid, j));
    const char *sn[MC_NSTRESS + 3] = {"stress_xx", "stress_yy", "stress_zz",
                                      "stress_xy", "stress_yz", "stress_xz",
                                      "von_mises", "hydrostatic", "tresca"};
    const double *sa[MC_NSTRESS + 3] = {r->stress[0], r->stress[1], r->stress[2],
                                        r->stress[3], r->stress[4], r->stress[5],
                                        r->von_mises, r->hydrostatic, r->tresca};
    size_t n = NX * NY;
    for (int a = 0; a < MC_NSTRESS + 3; a++) {
        const unsigned char *d = vtk_block(b, len, sn[a], &nb);
        ck_assert_uint_eq(nb, 8 * n * NL);
        for (int k = 0; k < NL; k++)
            ck_assert_mem_eq(d + 8 * n * k, sa[a] + n * (NL - 1 - k), 8 * n);
    }
    mc_free(b);
}

static void check_all(const char *dir, const mc_scene *s, const mc_results *r)
{
    check_npy2(dir, "pressure.npy", r->pressure);
    check_npy2(dir, "gap.npy", r->gap);
    check_npy2(dir, "displacement.npy", r->displacement);
    check_npy2(dir, "topography.npy", r->topography);
    const char *stress_files[] = {"stress_xx.npy", "stress_yy.npy", "stress_zz.npy",
                                  "stress_xy.npy", "stress_yz.npy", "stress_xz.npy",
                                  "von_mises.npy", "hydrostatic.npy", "depths.csv", "axis.csv"};
    for (int k = 0; k < 10; k++)
        ck_assert_int_eq(exists(dir, stress_files[k]), r->nlayers > 0);
    if (r->nlayers > 0) {
        for (int c = 0; c < MC_NSTRESS; c++)
            check_npy3(dir, stress_files[c], r->stress[c]);
        check_npy3(dir, "von_mises.npy", r->von_mises);
        check_npy3(dir, "hydrostatic.npy", r->hydrostatic);
    }
    check_csv(dir, r);
    check_summary(dir, s, r);
    ck_assert_int_eq(exists(dir, "field.vti"), s->output.vtk);
    if (s->output.vtk)
        check_vtk(dir, r);
    /* the output table says which files a run writes: exactly those are there */
    for (int i = 0; i < mc_output_file_count(); i++)
        ck_assert_msg(exists(dir, mc_output_file_name(i)) == mc_output_file_written(i, s, r),
                      "%s: on disk %d, table %d", mc_output_file_name(i),
                      exists(dir, mc_output_file_name(i)), mc_output_file_written(i, s, r));
    char joined[2048], *names = listing(dir);
    mc_output_files_joined(s, r, ", ", joined, sizeof joined);
    for (int i = 0; i < mc_output_file_count(); i++) {
        char line[128];
        snprintf(line, sizeof line, "%s\n", mc_output_file_name(i));
        ck_assert_int_eq(strstr(joined, mc_output_file_name(i)) != NULL,
                         mc_output_file_written(i, s, r));
        ck_assert_int_eq(strstr(names, line) != NULL, mc_output_file_written(i, s, r));
    }
    free(names);
}

/* The output table: names unique, help present without '|'; docs/outputs.md is generated from it. */
#define OUT_DOC_MARK "<!-- generated by mc_output_reference_markdown()"
START_TEST(test_output_table_and_doc)
{
    ck_assert_int_ge(mc_output_file_count(), 1);
    for (int i = 0; i < mc_output_file_count(); i++) {
        ck_assert_ptr_nonnull(mc_output_file_name(i));
        ck_assert_ptr_nonnull(mc_output_file_help(i));
        ck_assert(!strchr(mc_output_file_help(i), '|'));
        for (int j = 0; j < i; j++)
            ck_assert_str_ne(mc_output_file_name(i), mc_output_file_name(j));
    }
    ck_assert_ptr_null(mc_output_file_name(mc_output_file_count()));
    char *md = mc_output_reference_markdown();
    ck_assert_ptr_nonnull(md);
    for (int i = 0; i < mc_output_file_count(); i++) {
        char cell[128];
        snprintf(cell, sizeof cell, "| `%s` |", mc_output_file_name(i));
        ck_assert_msg(strstr(md, cell), "reference lacks %s", cell);
    }
    const char *path = "docs/outputs.md";
    FILE *f = fopen(path, "rb");
    ck_assert_msg(f != NULL, "cannot open %s (run the tests from the repository root)", path);
    static char doc[1 << 16];
    size_t n = fread(doc, 1, sizeof doc - 1, f);
    fclose(f);
    doc[n] = '\0';
    const char *gen = strstr(doc, OUT_DOC_MARK);
    ck_assert_msg(gen && gen > doc, "%s: no hand-written introduction before the generated part",
                  path);
    if (strcmp(gen, md) != 0) {
        char fresh[700];
        snprintf(fresh, sizeof fresh, "%s/outputs.md", test_tmpdir_kept());
        FILE *o = fopen(fresh, "wb");
        if (o) {
            fwrite(doc, 1, (size_t)(gen - doc), o);
            fputs(md, o);
            fclose(o);
        }
        mc_free(md);
        ck_abort_msg("%s is out of date with the output table in src/pipeline/output.c; the "
                     "regenerated file is %s (copy it over)",
                     path, fresh);
    }
    mc_free(md);
}
END_TEST

START_TEST(test_write_all_combinations)
{
    /* with/without stress x with/without vtk, each into a fresh and into a reused directory */
    for (int stress = 0; stress <= 1; stress++)
        for (int vtk = 0; vtk <= 1; vtk++) {
            const char *dir = test_tmpdir();
            mc_results r;
            mc_scene s;
            make_results(&r, stress);
            make_scene(&s, vtk);
            mc_error err = {0};
            ck_assert_int_eq(mc_output_prepare(dir, &err), MC_OK);
            ck_assert_msg(mc_output_write(dir, &s, &r, &err) == MC_OK, "%s", err.msg);
            check_all(dir, &s, &r);
            ck_assert_msg(mc_output_write(dir, &s, &r, &err) == MC_OK, "%s", err.msg);
            check_all(dir, &s, &r);
            mc_results_free(&r);
            test_rm_tree(dir);
        }
}
END_TEST

START_TEST(test_stale_files_removed)
{
    const char *dir = test_tmpdir();
    mc_results r;
    mc_scene s;
    mc_error err = {0};
    make_results(&r, 1);
    make_scene(&s, 1);
    ck_assert_int_eq(mc_output_write(dir, &s, &r, &err), MC_OK);
    ck_assert(exists(dir, "von_mises.npy") && exists(dir, "stress.vtr"));
    /* an unrelated file of the user's survives */
    FILE *f = fopen(path_in(dir, "notes.txt"), "w");
    fputs("mine\n", f);
    fclose(f);
    mc_results_free(&r);
    make_results(&r, 0);
    make_scene(&s, 0);
    ck_assert_int_eq(mc_output_write(dir, &s, &r, &err), MC_OK);
    ck_assert(exists(dir, "notes.txt"));
    ck_assert_int_eq(unlink(path_in(dir, "notes.txt")), 0);
    check_all(dir, &s, &r); /* also: the listing equals the summary's file list */
    mc_results_free(&r);
    test_rm_tree(dir);
}
END_TEST

START_TEST(test_prepare)
{
    /* prepare checks and creates nothing: the directory appears with the results only */
    const char *tmp = test_tmpdir();
    mc_error err = {0};
    char dir[600];
    snprintf(dir, sizeof dir, "%s/a/b//c/", tmp);
    ck_assert_msg(mc_output_prepare(dir, &err) == MC_OK, "%s", err.msg);
    ck_assert_int_eq(mc_output_prepare(dir, &err), MC_OK); /* idempotent */
    char *l = listing(tmp);
    ck_assert_str_eq(l, "");
    free(l);
    ck_assert_int_eq(mc_output_prepare("", &err), MC_ERR_INPUT);
    mc_results r;
    mc_scene s;
    make_results(&r, 0);
    make_scene(&s, 0);
    ck_assert_msg(mc_output_write(dir, &s, &r, &err) == MC_OK, "%s", err.msg);
    struct stat sb;
    ck_assert(stat(path_in(tmp, "a/b/c"), &sb) == 0 && S_ISDIR(sb.st_mode));
    ck_assert_msg(mc_output_prepare(dir, &err) == MC_OK, "%s", err.msg); /* existing now */
    mc_results_free(&r);
    test_rm_tree(tmp);
}
END_TEST

START_TEST(test_unwritable)
{
    /* A path under a regular file cannot be a directory, even for root. */
    const char *tmp = test_tmpdir();
    char *file = path_in(tmp, "file");
    FILE *f = fopen(file, "w");
    fputs("keep\n", f);
    fclose(f);
    char dir[600];
    snprintf(dir, sizeof dir, "%s/file/out", tmp);
    mc_error err = {0};
    ck_assert_int_eq(mc_output_prepare(dir, &err), MC_ERR_ENV);
    ck_assert_msg(strstr(err.msg, dir) && strstr(err.msg, "Not a directory"), "%s", err.msg);

    mc_results r;
    mc_scene s;
    make_results(&r, 1);
    make_scene(&s, 1);
    ck_assert_int_eq(mc_output_write(dir, &s, &r, &err), MC_ERR_ENV);
    ck_assert_msg(strstr(err.msg, dir), "%s", err.msg);
    char *l = listing(tmp);
    ck_assert_str_eq(l, "file\n");
    free(l);
    struct stat sb;
    ck_assert(stat(file, &sb) == 0 && S_ISREG(sb.st_mode) && sb.st_size == 5);
    mc_results_free(&r);
    test_rm_tree(tmp);
}
END_TEST

START_TEST(test_target_is_directory)
{
    /* A directory where a result file goes: refused before DIR is touched. */
    const char *dir = test_tmpdir();
    mc_results r;
    mc_scene s;
    mc_error err = {0};
    make_results(&r, 0);
    make_scene(&s, 0);
    ck_assert_int_eq(mc_output_write(dir, &s, &r, &err), MC_OK);
    ck_assert_int_eq(mkdir(path_in(dir, "axis.csv"), 0700), 0);
    char *before = snapshot(dir);
    mc_results_free(&r);
    make_results(&r, 1);
    r.pressure[0] = 7.0; /* different data */
    ck_assert_int_eq(mc_output_write(dir, &s, &r, &err), MC_ERR_ENV);
    ck_assert_msg(strstr(err.msg, "'axis.csv' is a directory"), "%s", err.msg);
    char *after = snapshot(dir);
    ck_assert_str_eq(after, before);
    free(before);
    free(after);
    mc_results_free(&r);
    test_rm_tree(dir);
}
END_TEST

START_TEST(test_fault_injection)
{
    /* DIR holds a complete earlier run (stress, vtk). Each failing allocation n must leave it
     * byte for byte as it was (no new files, no staging directory); the first n that succeeds
     * replaces it by the new set. Run under ASan to show that no path leaks. */
    const char *dir = test_tmpdir();
    mc_results old, r;
    mc_scene s_old, s;
    mc_error err = {0};
    make_results(&old, 1);
    make_scene(&s_old, 1);
    ck_assert_int_eq(mc_output_write(dir, &s_old, &old, &err), MC_OK);
    char *before = snapshot(dir);
    make_results(&r, 0);
    make_scene(&s, 1);
    r.pressure[JMAX * NX + IMAX] = 6.0;
    r.contact.p_max = 6.0;
    int failures = 0;
    for (long n = 1;; n++) {
        mc_error e = {0};
        mc_alloc_fail_at(n);
        int st = mc_output_write(dir, &s, &r, &e);
        mc_alloc_fail_at(0);
        if (st == MC_OK)
            break;
        failures++;
        ck_assert_msg(st == MC_ERR_NOMEM, "n = %ld: %s", n, e.msg);
        ck_assert(e.msg[0] != '\0');
        char *after = snapshot(dir);
        ck_assert_msg(strcmp(after, before) == 0, "n = %ld changed DIR:\n%s", n, after);
        free(after);
        ck_assert_int_lt(n, 100000);
    }
    ck_assert_int_gt(failures, 20); /* the loop really went through the JSON building */
    free(before);
    json_error_t je;
    json_t *root = json_load_file(path_in(dir, "summary.json"), 0, &je);
    ck_assert_msg(root != NULL, "%s", je.text);
    json_t *contact = json_object_get(root, "contact");
    ck_assert_double_eq(json_number_value(json_object_get(contact, "p_max")), 6.0);
    json_decref(root);
    ck_assert(!exists(dir, "von_mises.npy") && !exists(dir, "stress.vtr"));
    ck_assert(exists(dir, "field.vti"));
    check_npy2(dir, "pressure.npy", r.pressure);
    mc_results_free(&old);
    mc_results_free(&r);
    test_rm_tree(dir);
}
END_TEST

START_TEST(test_strings_and_seed)
{
    const char *dir = test_tmpdir();
    mc_results r;
    mc_scene s;
    mc_error err = {0};
    make_results(&r, 0);
    make_scene(&s, 0);
    snprintf(s.path, sizeof s.path, "cases/caf\xe9-\xc3\xa9.ini"); /* Latin-1 byte, then UTF-8 */
    r.roughness_seed = 18446744073709551615ULL;
    r.contact.solver = NULL;
    s.load.pressure_cap = 2e9;
    ck_assert_int_eq(mc_output_write(dir, &s, &r, &err), MC_OK);
    json_t *root = json_load_file(path_in(dir, "summary.json"), 0, NULL);
    ck_assert_ptr_nonnull(root);
    ck_assert_str_eq(json_string_value(json_object_get(root, "case")), "cases/caf?-\xc3\xa9.ini");
    ck_assert_str_eq(json_string_value(json_object_get(jobj(root, "roughness"), "seed")),
                     "18446744073709551615");
    ck_assert(json_is_null(json_object_get(jobj(root, "contact"), "solver")));
    ck_assert_double_eq(jreal(jobj(root, "load"), "pressure_cap"), 2e9);
    json_decref(root);
    mc_results_free(&r);
    test_rm_tree(dir);
}
END_TEST

START_TEST(test_profile_ties)
{
    /* zero pressure everywhere: the profile runs through the central row, not row 0 */
    const char *dir = test_tmpdir();
    mc_results r;
    mc_scene s;
    mc_error err = {0};
    make_results(&r, 0);
    make_scene(&s, 0);
    memset(r.pressure, 0, sizeof(double) * NX * NY);
    ck_assert_int_eq(mc_output_write(dir, &s, &r, &err), MC_OK);
    int n;
    double v[4];
    char **l = read_lines(path_in(dir, "profile_x.csv"), &n);
    ck_assert_int_eq(n, NX + 1);
    for (int i = 0; i < NX; i++) {
        csv_values(l[i + 1], v, 4);
        ck_assert_double_eq(v[2], r.gap[(NY / 2) * NX + i]);
    }
    free_lines(l, n);
    mc_results_free(&r);
    test_rm_tree(dir);
}
END_TEST

START_TEST(test_bad_results)
{
    const char *dir = test_tmpdir();
    mc_results r;
    mc_scene s;
    mc_error err = {0};
    make_results(&r, 1);
    make_scene(&s, 1);
    mc_free(r.tresca);
    r.tresca = NULL;
    ck_assert_int_eq(mc_output_write(dir, &s, &r, &err), MC_ERR_INTERNAL);
    mc_free(r.gap);
    r.gap = NULL;
    ck_assert_int_eq(mc_output_write(dir, &s, &r, &err), MC_ERR_INTERNAL);
    char *l = listing(dir);
    ck_assert_str_eq(l, "");
    free(l);
    mc_results_free(&r);
    test_rm_tree(dir);
}
END_TEST

START_TEST(test_results_free)
{
    mc_results r;
    memset(&r, 0, sizeof r);
    mc_results_free(&r); /* zeroed: no-op */
    mc_results_free(NULL);
    make_results(&r, 1);
    mc_free(r.stress[2]); /* half-filled */
    r.stress[2] = NULL;
    mc_results_free(&r);
    const unsigned char *b = (const unsigned char *)&r;
    for (size_t k = 0; k < sizeof r; k++)
        ck_assert_uint_eq(b[k], 0);
}
END_TEST

Suite *suite_output(void);
Suite *suite_output(void)
{
    Suite *s = suite_create("output");
    TCase *tc = tcase_create("output");
    tcase_set_timeout(tc, 300);
    tcase_add_test(tc, test_write_all_combinations);
    tcase_add_test(tc, test_stale_files_removed);
    tcase_add_test(tc, test_prepare);
    tcase_add_test(tc, test_unwritable);
    tcase_add_test(tc, test_target_is_directory);
    tcase_add_test(tc, test_fault_injection);
    tcase_add_test(tc, test_strings_and_seed);
    tcase_add_test(tc, test_profile_ties);
    tcase_add_test(tc, test_bad_results);
    tcase_add_test(tc, test_results_free);
    tcase_add_test(tc, test_output_table_and_doc);
    suite_add_tcase(s, tc);
    return s;
}
