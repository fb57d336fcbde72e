/* Kind and identity of a file system entry, for the deck reader.
 *
 * Fortran cannot tell a regular file from a directory, a FIFO or a device:
 * opening a FIFO blocks until a writer appears, and /dev/zero never ends.
 * stat() answers without opening anything; its struct is libc's own, so
 * it is read here rather than mirrored in Fortran. The device and inode
 * numbers identify a file whatever path names it (include recursion). */
#include <sys/stat.h>

enum { kind_missing = 0, kind_regular = 1, kind_directory = 2, kind_other = 3 };

int cfe2d_file_kind(const char *path, long long *device, long long *inode)
{
    struct stat st;
    *device = 0;
    *inode = 0;
    if (stat(path, &st) != 0)
        return kind_missing;
    *device = (long long)st.st_dev;
    *inode = (long long)st.st_ino;
    if (S_ISREG(st.st_mode))
        return kind_regular;
    if (S_ISDIR(st.st_mode))
        return kind_directory;
    return kind_other;
}
