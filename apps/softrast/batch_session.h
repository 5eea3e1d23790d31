/* batch_session.h - what every batch command shares (batch_session.c):
 * the batch options, the input list and its outputs' names, the check
 * that no output replaces an input, the writer, the log, the progress
 * line and the exit status.  `softrast render` drives it with its own
 * read-ahead (batch.c); `softrast svg` hands it one callback per input,
 * which several threads call at once (batch_session_each). */
#ifndef SR_BATCH_SESSION_H
#define SR_BATCH_SESSION_H

#include "batch.h"
#include "batch_writer.h"

#include <stdio.h>
#include <sys/types.h>

/* The batch options every batch command takes. */
typedef struct batch_common {
    const char *list;          /* --batch LIST */
    const char *output_dir;    /* --output-dir DIR (default .) */
    const char *name;          /* --name PATTERN */
    const char *log;           /* --log FILE.jsonl */
    const char *shard, *shard_count;
    bool skip_existing;
    bool any;                  /* one of them was given */
} batch_common;

/* The help text of batch_common's options (items of the command's
 * batch group), and the paragraph on the output and exit status that
 * ends the group. */
void batch_help_options(FILE *f);
void batch_help_status(FILE *f);

/* If argv[*i] is one of batch_common's options, take it and its value
 * (*i then at the value): 1; 0 when it is not one; an exit status after
 * one line for a missing or empty value. */
int batch_take_option(batch_common *c, int argc, char **argv, int *i);

/* Whether the arguments ask for a batch: a batch option, several
 * inputs, or one that is a directory or a pattern that names no file. */
bool batch_asked(const batch_common *c, const char *const *args, size_t count);

/* The monotonic clock in milliseconds, for the log's times. */
double batch_now_ms(void);

/* An input's identity: an output is never one of them, by any name. */
typedef struct batch_file_id {
    dev_t dev;
    ino_t ino;
} batch_file_id;

typedef struct batch_session {
    const batch_common *opts;
    batch_list list;
    batch_shard shard;
    batch_file_id *ids;        /* the inputs', sorted */
    size_t id_count;
    batch_writer writer;
    batch_progress progress;
    size_t ok;                 /* inputs written (or put on a sheet) */
    int log_fd;
    int log_errno;             /* why the log could not be written, or 0 */
    bool running;              /* between batch_session_begin and _end */
} batch_session;

/* Resolve the shard and list the inputs: the arguments (files,
 * directories searched for names `takes` accepts, glob patterns), then
 * --batch's list, sorted; `none` says there are none ("render: no
 * models").  -1,
 * or an exit status after one line. */
int batch_session_gather(batch_session *s, const batch_common *c, const char *const *args,
                         size_t count, batch_takes_fn takes, const char *none);
/* Name the outputs DIR/PATTERN: --output-dir and --name, or
 * default_name. */
int batch_session_name(batch_session *s, const char *default_name);
/* Open the log and note the inputs' identities.  -1 or an exit status. */
int batch_session_open(batch_session *s);
/* How many inputs of the list are this shard's. */
size_t batch_session_mine(const batch_session *s);
/* Start the progress line (records in all) and the writer's threads. */
void batch_session_begin(batch_session *s, size_t records, int writers);
/* Write what the writer holds, stop it, draw the last progress and give
 * the exit status: 0, or some or all failed. */
int batch_session_end(batch_session *s);
/* Close the log (a log that could not be written makes `status`
 * EXIT_FAILURE_RUN) and free the list. */
int batch_session_close(batch_session *s, int status);

/* Whether an output may be written: not a directory, not an input of the
 * batch; false after cli_error says why (`opt` names the option that
 * named it). */
bool batch_session_output_ok(const batch_session *s, const char *output, const char *opt);
/* A non-empty regular file: --skip-existing leaves it. */
bool batch_exists_whole(const char *path);
/* One line on stderr for an input, naming it unless `message` does. */
void batch_session_report(batch_session *s, const char *input, const char *message);
/* An input is finished (a batch_done_fn, user the session): count,
 * report, log, redraw the progress. */
void batch_session_done(void *user, batch_record *rec, const char *message);

/* One input's image, drawn by a batch_draw_fn. */
typedef struct batch_picture {
    const uint8_t *rgba;
    int width, height;
    cli_image_options image;
} batch_picture;

/* Draw `it` into *pic with slot `slot`'s own things (a context, a
 * framebuffer), rec's load_ms, render_ms and counts set: true, with
 * warnings in message if any; false with why in message.  Called on a
 * drawing thread; a slot is used by one thread at a time, and its
 * pixels stay until the batch releases it. */
typedef bool (*batch_draw_fn)(void *user, int slot, const batch_item *it, batch_picture *pic,
                              batch_record *rec, char *message, size_t size);
/* The slot's picture is handed to the writer (or failed): free what it
 * holds.  Called on the batch's thread. */
typedef void (*batch_release_fn)(void *user, int slot);

/* The most drawing threads, as the library's contexts take. */
enum { BATCH_DRAW_MAX_THREADS = 64 };
/* Drawn pictures wait for the batch's thread (in list order) while they
 * hold fewer bytes than this; a drawing that takes long then stops the
 * others only once its followers fill the slots. */
#define BATCH_DRAW_MAX_BYTES ((size_t)256 << 20)

/* How batch_session_each draws. */
typedef struct batch_drawer {
    batch_draw_fn draw;
    batch_release_fn release;  /* NULL: nothing to free */
    void *user;
    int threads;               /* drawing threads, 1 .. BATCH_DRAW_MAX_THREADS */
} batch_drawer;

/* The slots `threads` drawing threads use (0 .. slots-1): the drawings
 * in hand at most. */
int batch_draw_slots(int threads);

/* The shard's inputs in list order, between begin and end: each skipped
 * (--skip-existing), refused (its output) or drawn and handed to the
 * writer.  d->threads threads check and draw the inputs side by side
 * (batch_draw.c); this thread reports and hands them over in the order
 * of the list. */
void batch_session_each(batch_session *s, const batch_drawer *d);

#endif
