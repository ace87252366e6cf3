/* text_file.h - read a whole input file into memory (bounded, regular files
 * only, so that a path such as /dev/zero or a FIFO named by an input file
 * cannot hang or exhaust the reader). */
#ifndef RN_TEXT_FILE_H
#define RN_TEXT_FILE_H

#include <stddef.h>

#include "rodnet.h"

/* Read the regular file at path into *text (NUL-terminated, caller frees),
 * its length in *len.  RN_ERR_IO ("PATH: cannot open: reason", "PATH: not a
 * regular file", "PATH: larger than N bytes", ...) or RN_ERR_ALLOC, recorded
 * in ctx. */
rn_status rn_text_file_read(rn_context *ctx, const char *path, size_t max_bytes,
                            char **text, size_t *len);

#endif
