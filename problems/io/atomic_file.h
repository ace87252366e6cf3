/* atomic_file.h - write a file completely or not at all.
 *
 * The content goes to "<path>.tmp.<pid>" in the same directory, which is
 * renamed over path only when everything was written and flushed; on any
 * error the temporary file is removed and path is left as it was.
 * An existing path that is neither a regular file nor a directory (a device
 * such as /dev/null or /dev/stdout, a FIFO) is written in place instead:
 * a rename would replace the device by a regular file.
 */
#ifndef RN_ATOMIC_FILE_H
#define RN_ATOMIC_FILE_H

#include <stdio.h>

#include "rodnet.h"

/* Writes the content to f; returns RN_OK or an error (recorded in ctx). */
typedef rn_status (*rn_file_writer)(FILE *f, void *user, rn_context *ctx);

/* Run write(f, user, ctx) on a temporary file and rename it to path.
 * RN_ERR_IO (message "path: reason") if the file cannot be created, written,
 * flushed or renamed; the writer's status if it fails. */
rn_status rn_file_write_atomic(rn_context *ctx, const char *path, rn_file_writer write,
                               void *user);

/* Check early that path can be written (creates and removes the temporary
 * file); RN_ERR_IO with a message otherwise. */
rn_status rn_file_probe_writable(rn_context *ctx, const char *path);

/* Temporary files: the hook (NULL by default) is called with active = 1 just
 * before a temporary file is created and with active = 0 once it has been
 * renamed or removed; the name stays valid in between.  The rodnet command
 * sets it to remove the temporary files when a signal ends the process
 * (cli_signals.c); the library itself installs no signal handler. */
typedef void (*rn_file_temp_hook)(const char *tmp, int active);
void rn_file_set_temp_hook(rn_file_temp_hook hook);

#endif
