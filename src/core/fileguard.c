/* fileguard.c - refuse devices, FIFOs and oversized files before reading them (fileguard.h). */
#include "core/fileguard.h"

#include <sys/stat.h>

static const char *kind_of(mode_t m)
{
    if (S_ISCHR(m))
        return "a character device";
    if (S_ISBLK(m))
        return "a block device";
    if (S_ISFIFO(m))
        return "a FIFO or pipe";
    if (S_ISSOCK(m))
        return "a socket";
    return "not a file";
}

int mc_file_guard(const char *path, size_t max_bytes, const char *what, mc_error *err)
{
    struct stat sb;
    if (!path || stat(path, &sb) != 0 || S_ISDIR(sb.st_mode))
        return MC_OK; /* the open or read that follows names the reason */
    if (!what)
        what = "a file this program reads";
    if (!S_ISREG(sb.st_mode))
        return mc_fail(err, MC_ERR_INPUT, "%s: not a regular file (%s); %s must be a regular file",
                       path, kind_of(sb.st_mode), what);
    if (max_bytes && (unsigned long long)sb.st_size > (unsigned long long)max_bytes)
        return mc_fail(err, MC_ERR_INPUT, "%s: %lld bytes, larger than %zu MiB; not %s", path,
                       (long long)sb.st_size, max_bytes >> 20, what);
    return MC_OK;
}
