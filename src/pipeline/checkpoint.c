/* checkpoint.c - the running-in state on disk, written atomically (see checkpoint.h). */
#include "pipeline/checkpoint.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/alloc.h"
#include "core/dist.h"
#include "core/fileguard.h"

#define MAGIC "MCRUNIN"  /* 8 bytes with its NUL */
#define VERSION 1u
#define PATH_MAX_CK 4096

/* FNV-1a 64 (Fowler, Noll, Vo): a checksum of the bytes, not a cryptographic digest. */
#define FNV_OFFSET 14695981039346656037ull
#define FNV_PRIME 1099511628211ull

static uint64_t fnv(uint64_t h, const void *p, size_t n)
{
    const unsigned char *b = p;
    for (size_t i = 0; i < n; i++) {
        h ^= b[i];
        h *= FNV_PRIME;
    }
    return h;
}

/* The build guard: sizes of the types whose bytes are stored. */
typedef struct {
    char magic[8];
    uint32_t version;
    uint32_t size_double, size_row, size_long, size_record;
} header;

static void make_header(header *h)
{
    memset(h, 0, sizeof *h);
    memcpy(h->magic, MAGIC, sizeof h->magic);
    h->version = VERSION;
    h->size_double = sizeof(double);
    h->size_row = sizeof(mc_runin_row);
    h->size_long = sizeof(long);
    h->size_record = sizeof(mc_plastic_step);
}

typedef struct {
    FILE *f;
    uint64_t sum;
    int bad;
} writer;

static void put(writer *w, const void *p, size_t n)
{
    if (n == 0 || w->bad)
        return;
    w->sum = fnv(w->sum, p, n);
    if (fwrite(p, 1, n, w->f) != n)
        w->bad = 1;
}

static int path_of(char *buf, const char *dir, const char *name, mc_error *err)
{
    if (snprintf(buf, PATH_MAX_CK, "%s/%s", dir, name) >= PATH_MAX_CK)
        return mc_fail(err, MC_ERR_ENV, "checkpoint: path '%s/%s' too long", dir, name);
    return MC_OK;
}

int mc_checkpoint_write(const char *dir, const mc_checkpoint *c, mc_error *err)
{
    char path[PATH_MAX_CK], tmp[PATH_MAX_CK];
    int rc = path_of(path, dir, MC_CHECKPOINT_FILE, err);
    if (rc == MC_OK)
        rc = path_of(tmp, dir, MC_CHECKPOINT_FILE ".tmp", err);
    if (rc != MC_OK)
        return rc;
    if (mkdir(dir, 0777) != 0 && errno != EEXIST)
        return mc_fail(err, MC_ERR_ENV, "checkpoint: cannot create '%s': %s", dir,
                       strerror(errno));
    writer w = {.f = fopen(tmp, "wb"), .sum = FNV_OFFSET};
    if (!w.f)
        return mc_fail(err, MC_ERR_ENV, "checkpoint: cannot create '%s': %s", tmp,
                       strerror(errno));
    header h;
    make_header(&h);
    put(&w, &h, sizeof h);
    int32_t ints[6] = {c->nx, c->ny, c->nz, c->nsteps, c->done, c->nrec};
    int64_t nvol = c->nvol;
    put(&w, &c->case_hash, sizeof c->case_hash);
    put(&w, ints, sizeof ints);
    put(&w, &nvol, sizeof nvol);
    put(&w, &c->seconds, sizeof c->seconds);
    put(&w, c->rows, (size_t)c->done * sizeof *c->rows);
    put(&w, c->records, (size_t)c->nrec * sizeof *c->records);
    const size_t nv = (size_t)c->nvol, ncell = (size_t)c->nx * (size_t)c->ny;
    if (nv > 0) {
        put(&w, c->eps_p, 6 * nv * sizeof(double));
        put(&w, c->peq, nv * sizeof(double));
        put(&w, c->sig_r, 6 * nv * sizeof(double));
    }
    put(&w, c->u_r, ncell * sizeof(double));
    uint64_t sum = w.sum;
    put(&w, &sum, sizeof sum);
    int e = 0;
    if (w.bad || fflush(w.f) != 0 || fsync(fileno(w.f)) != 0)
        e = errno ? errno : EIO;
    if (fclose(w.f) != 0 && !e)
        e = errno;
    if (!e && rename(tmp, path) != 0)
        e = errno;
    if (e) {
        unlink(tmp);
        return mc_fail(err, MC_ERR_ENV, "checkpoint: cannot write '%s': %s", path, strerror(e));
    }
    /* the rename itself on the disk: fsync the directory (best effort) */
    int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd >= 0) {
        fsync(fd);
        close(fd);
    }
    return MC_OK;
}

int mc_checkpoint_exists(const char *dir)
{
    char path[PATH_MAX_CK];
    struct stat sb;
    return snprintf(path, sizeof path, "%s/%s", dir, MC_CHECKPOINT_FILE) < (int)sizeof path &&
           stat(path, &sb) == 0 && S_ISREG(sb.st_mode);
}

typedef struct {
    const unsigned char *p;
    size_t left;
} reader;

static int take(reader *r, void *dst, size_t n)
{
    if (n > r->left)
        return 0;
    if (n)
        memcpy(dst, r->p, n);
    r->p += n;
    r->left -= n;
    return 1;
}

/* A heap copy of the next n doubles (NULL if short or out of memory: *nomem says which). */
static double *take_doubles(reader *r, size_t n, int *nomem)
{
    if (n > r->left / sizeof(double))
        return NULL;
    double *a = mc_malloc(n ? n * sizeof *a : 1);
    if (!a) {
        *nomem = 1;
        return NULL;
    }
    take(r, a, n * sizeof *a);
    return a;
}

void mc_checkpoint_free(mc_checkpoint *c)
{
    mc_free(c->rows);
    mc_free(c->eps_p);
    mc_free(c->peq);
    mc_free(c->sig_r);
    mc_free(c->u_r);
    mc_free(c->records);
    memset(c, 0, sizeof *c);
}

static int corrupt(const char *path, const char *why, mc_error *err)
{
    return mc_fail(err, MC_ERR_INPUT,
                   "checkpoint '%s' cannot be resumed: %s; run without --resume to start over",
                   path, why);
}

/* The first field of c whose values are not all finite (NULL: none): a file written by a run
 * that went wrong, or altered with its checksum recomputed, is refused at read time, not at the
 * first solve of the resumed run. */
static const char *nonfinite_field(const mc_checkpoint *c, char *buf, size_t len)
{
    const struct {
        const char *name;
        const double *v;
        size_t n;
    } f[] = {{"the plastic strain", c->eps_p, 6 * (size_t)c->nvol},
             {"the accumulated plastic strain", c->peq, (size_t)c->nvol},
             {"the residual stress", c->sig_r, 6 * (size_t)c->nvol},
             {"the residual displacement", c->u_r, (size_t)c->nx * (size_t)c->ny},
             {"the elapsed seconds", &c->seconds, 1}};
    for (size_t i = 0; i < sizeof f / sizeof f[0]; i++)
        for (size_t k = 0; f[i].v && k < f[i].n; k++)
            if (!isfinite(f[i].v[k])) {
                snprintf(buf, len, "%s holds %g at value %zu of %zu (not finite)", f[i].name,
                         f[i].v[k], k + 1, f[i].n);
                return buf;
            }
    return NULL;
}

/* The checkpoint file's bytes on this process (*buf mc_malloc'ed, *len bytes and a NUL). */
static int read_bytes(const char *path, unsigned char **bufp, size_t *lenp, mc_error *err)
{
    /* a device or FIFO in its place would be read forever or block the open */
    int rc = mc_file_guard(path, MC_FILE_MAX_CHECKPOINT, "a checkpoint", err);
    if (rc != MC_OK)
        return rc;
    FILE *f = fopen(path, "rb");
    if (!f)
        return mc_fail(err, MC_ERR_INPUT,
                       "no checkpoint to resume: '%s' %s (run without --resume to start)", path,
                       errno == ENOENT ? "does not exist" : strerror(errno));
    unsigned char *buf = NULL;
    long size = -1;
    if (fseek(f, 0, SEEK_END) == 0)
        size = ftell(f);
    if (size >= 0 && fseek(f, 0, SEEK_SET) == 0 && (buf = mc_malloc((size_t)size + 1)) &&
        fread(buf, 1, (size_t)size, f) != (size_t)size)
        size = -1;
    fclose(f);
    if (!buf) {
        if (size >= 0)
            return mc_fail(err, MC_ERR_NOMEM, "checkpoint '%s': out of memory (%ld bytes)", path,
                           size);
        return corrupt(path, "it cannot be read", err);
    }
    if (size < 0) {
        mc_free(buf);
        return corrupt(path, "it cannot be read", err);
    }
    buf[size] = '\0';
    *bufp = buf;
    *lenp = (size_t)size;
    return MC_OK;
}

int mc_checkpoint_read(const char *dir, mc_checkpoint *c, mc_error *err)
{
    memset(c, 0, sizeof *c);
    char path[PATH_MAX_CK];
    int rc = path_of(path, dir, MC_CHECKPOINT_FILE, err);
    if (rc != MC_OK)
        return rc;
    /* under mpirun rank 0 alone reads it and every rank receives its bytes or its error
     * (core/dist.h): DIR/checkpoint/ need only be visible to rank 0, which holds DIR */
    unsigned char *buf = NULL;
    size_t len = 0;
    rc = mc_dist_rank() == 0 ? read_bytes(path, &buf, &len, err) : MC_OK;
    if ((rc = mc_dist_share_read(rc, &buf, &len, path, err)) != MC_OK)
        return rc;
    const long size = (long)len;
    header want, got;
    make_header(&want);
    uint64_t sum;
    if ((size_t)size < sizeof got + sizeof sum) {
        mc_free(buf);
        return corrupt(path, "it is truncated", err);
    }
    memcpy(&got, buf, sizeof got);
    memcpy(&sum, buf + size - (long)sizeof sum, sizeof sum);
    rc = MC_OK;
    if (memcmp(got.magic, want.magic, sizeof got.magic) != 0)
        rc = corrupt(path, "it is not a microcontact checkpoint", err);
    else if (got.version != want.version || got.size_double != want.size_double ||
             got.size_row != want.size_row || got.size_long != want.size_long ||
             got.size_record != want.size_record)
        rc = corrupt(path, "it was written by another version or build of microcontact", err);
    else if (fnv(FNV_OFFSET, buf, (size_t)size - sizeof sum) != sum)
        rc = corrupt(path, "its checksum differs (a torn or altered file)", err);
    if (rc != MC_OK) {
        mc_free(buf);
        return rc;
    }
    reader r = {buf + sizeof got, (size_t)size - sizeof got - sizeof sum};
    int32_t ints[6] = {0};
    int64_t nvol = 0;
    int ok = take(&r, &c->case_hash, sizeof c->case_hash) && take(&r, ints, sizeof ints) &&
             take(&r, &nvol, sizeof nvol) && take(&r, &c->seconds, sizeof c->seconds);
    c->nx = ints[0];
    c->ny = ints[1];
    c->nz = ints[2];
    c->nsteps = ints[3];
    c->done = ints[4];
    c->nrec = ints[5];
    c->nvol = (long)nvol;
    ok = ok && c->nx > 0 && c->ny > 0 && c->nz >= 0 && nvol >= 0 && c->done >= 0 &&
         c->done <= c->nsteps && c->nrec >= 0 && c->nrec <= c->done;
    int nomem = 0;
    if (ok) {
        size_t nrow = (size_t)c->done * sizeof *c->rows;
        ok = nrow <= r.left && (c->rows = mc_malloc(nrow ? nrow : 1)) != NULL;
        nomem = !ok && nrow <= r.left;
        ok = ok && take(&r, c->rows, nrow);
    }
    if (ok) {
        size_t nb = (size_t)c->nrec * sizeof *c->records;
        ok = nb <= r.left && (c->records = mc_malloc(nb ? nb : 1)) != NULL;
        nomem = !ok && nb <= r.left;
        ok = ok && take(&r, c->records, nb);
    }
    const size_t nv = (size_t)c->nvol, ncell = (size_t)c->nx * (size_t)c->ny;
    if (ok && nv > 0)
        ok = (c->eps_p = take_doubles(&r, 6 * nv, &nomem)) &&
             (c->peq = take_doubles(&r, nv, &nomem)) &&
             (c->sig_r = take_doubles(&r, 6 * nv, &nomem));
    if (ok)
        ok = (c->u_r = take_doubles(&r, ncell, &nomem)) != NULL && r.left == 0;
    mc_free(buf);
    if (!ok) {
        mc_checkpoint_free(c);
        if (nomem)
            return mc_fail(err, MC_ERR_NOMEM, "checkpoint '%s': out of memory", path);
        return corrupt(path, "its contents do not add up", err);
    }
    char why[160];
    if (nonfinite_field(c, why, sizeof why)) {
        mc_checkpoint_free(c);
        return corrupt(path, why, err);
    }
    return MC_OK;
}

void mc_checkpoint_remove(const char *dir)
{
    char path[PATH_MAX_CK];
    if (snprintf(path, sizeof path, "%s/%s", dir, MC_CHECKPOINT_FILE) < (int)sizeof path)
        unlink(path);
    if (snprintf(path, sizeof path, "%s/%s.tmp", dir, MC_CHECKPOINT_FILE) < (int)sizeof path)
        unlink(path);
    rmdir(dir);
}
