/* file.c - whole files into memory (file.h). */
#include "io/file.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "core/alloc.h"
#include "core/dist.h"
#include "core/fileguard.h"

/* This process's read (the serial program's, and rank 0's under mpirun). */
static int read_limited(const char *path, size_t max_bytes, const char *what, unsigned char **buf,
                        size_t *len, mc_error *err)
{
    *buf = NULL;
    *len = 0;
    FILE *f = fopen(path, "rb");
    if (!f)
        return mc_fail(err, MC_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    struct stat sb;
    size_t cap = 4096;
    if (fstat(fileno(f), &sb) == 0 && S_ISREG(sb.st_mode) && sb.st_size > 0 &&
        (unsigned long long)sb.st_size < (unsigned long long)SIZE_MAX - 1)
        cap = (size_t)sb.st_size + 1;
    unsigned char *b = mc_malloc(cap);
    if (!b) {
        fclose(f);
        return mc_fail(err, MC_ERR_NOMEM, "%s: no memory to read %zu bytes", path, cap);
    }
    size_t n = 0;
    for (;;) {
        n += fread(b + n, 1, cap - n, f);
        if (ferror(f)) {
            int e = errno;
            mc_free(b);
            fclose(f);
            return mc_fail(err, MC_ERR_IO, "%s: cannot read: %s", path, strerror(e));
        }
        if (n < cap)
            break; /* end of file; one spare byte left for the terminator */
        if (max_bytes && n > max_bytes) { /* also a device that never ends (/dev/zero) */
            mc_free(b);
            fclose(f);
            return mc_fail(err, MC_ERR_INPUT, "%s: larger than %zu MiB; not %s", path,
                           max_bytes >> 20, what ? what : "a file this program reads");
        }
        if (cap > SIZE_MAX / 2) {
            mc_free(b);
            fclose(f);
            return mc_fail(err, MC_ERR_NOMEM, "%s: file too large", path);
        }
        unsigned char *nb = mc_malloc(cap * 2);
        if (!nb) {
            mc_free(b);
            fclose(f);
            return mc_fail(err, MC_ERR_NOMEM, "%s: no memory to read %zu bytes", path, cap * 2);
        }
        memcpy(nb, b, n);
        mc_free(b);
        b = nb;
        cap *= 2;
    }
    fclose(f);
    if (max_bytes && n > max_bytes) {
        mc_free(b);
        return mc_fail(err, MC_ERR_INPUT, "%s: larger than %zu MiB; not %s", path,
                       max_bytes >> 20, what ? what : "a file this program reads");
    }
    b[n] = '\0';
    *buf = b;
    *len = n;
    return MC_OK;
}

/* The guard and the read, on this process. */
static int read_data(const char *path, size_t max_bytes, const char *what, unsigned char **buf,
                     size_t *len, mc_error *err)
{
    int st = mc_file_guard(path, max_bytes, what, err);
    return st != MC_OK ? st : read_limited(path, max_bytes, what, buf, len, err);
}

/* Under mpirun rank 0 alone opens the file; its bytes, or its error, go to every rank
 * (core/dist.h): the same input on all ranks, and one failure reported alike by all. Serially
 * (and in the serial program, where mc_dist_rank() is 0) the read is this process's own. */
int mc_io_read_limited(const char *path, size_t max_bytes, const char *what, unsigned char **buf,
                       size_t *len, mc_error *err)
{
    *buf = NULL;
    *len = 0;
    int st = mc_dist_rank() == 0 ? read_limited(path, max_bytes, what, buf, len, err) : MC_OK;
    return mc_dist_share_read(st, buf, len, path, err);
}

int mc_io_read_data(const char *path, size_t max_bytes, const char *what, unsigned char **buf,
                    size_t *len, mc_error *err)
{
    *buf = NULL;
    *len = 0;
    int st = mc_dist_rank() == 0 ? read_data(path, max_bytes, what, buf, len, err) : MC_OK;
    return mc_dist_share_read(st, buf, len, path, err);
}

int mc_io_read_file(const char *path, unsigned char **buf, size_t *len, mc_error *err)
{
    return mc_io_read_data(path, MC_FILE_MAX_SURFACE, "a data file", buf, len, err);
}
