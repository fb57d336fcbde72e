/* Create a directory and its missing parents, like mkdir -p, for
 * --output-dir.
 *
 * Fortran has no portable way to create a directory (and calling the
 * shell for it would depend on the shell and quoting). mkdir() is called
 * for every prefix of the path that ends at a '/', then for the whole
 * path; an entry that already exists must be a directory. On failure the
 * prefix that could not be made and the reason go to msg. */
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>

/* One level: made, or already there as a directory (or a link to one). */
static int make_one(const char *path)
{
    struct stat st;
    if (mkdir(path, 0777) == 0)
        return 0;
    if (errno != EEXIST)
        return errno;
    if (stat(path, &st) != 0)
        return errno;
    return S_ISDIR(st.st_mode) ? 0 : ENOTDIR;
}

/* Returns 0 when path is a directory afterwards, else an errno value with
 * "prefix: reason" in msg (msglen bytes, always NUL-terminated). */
int cfe2d_make_dirs(const char *path, char *msg, int msglen)
{
    char buf[4096];
    size_t n = strlen(path), k;
    int err = 0;
    if (msglen > 0)
        msg[0] = '\0';
    if (n == 0)
        err = ENOENT;
    else if (n >= sizeof buf)
        err = ENAMETOOLONG;
    if (err != 0) {
        if (msglen > 0)
            snprintf(msg, (size_t)msglen, "%s: %s", path, strerror(err));
        return err;
    }
    memcpy(buf, path, n + 1);
    /* each prefix ending before a '/' (not the root's own '/'), then all */
    for (k = 1; k <= n; ++k) {
        if (k < n && buf[k] != '/')
            continue;
        if (k < n && buf[k - 1] == '/')
            continue;   /* "a//b": the empty component is no new level */
        buf[k] = '\0';
        err = make_one(buf);
        if (err != 0) {
            if (msglen > 0)
                snprintf(msg, (size_t)msglen, "%s: %s", buf, strerror(err));
            return err;
        }
        if (k < n)
            buf[k] = '/';
    }
    return 0;
}
