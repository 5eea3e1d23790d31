/* batch_writer.c - a batch's image files, written on a thread of their
 * own: while it compresses one image and waits for the disk to take it
 * (each output is fsync'd before it is renamed into place), the batch
 * reads and draws the next model.  One image is in hand at a time; the
 * writer has its own copy of the pixels, so the framebuffer can be drawn
 * again at once.  It compresses on one thread: the render job's context
 * is busy drawing. */
#include "batch_writer.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

bool batch_make_parents(const char *path, sr_io_error *err)
{
    char dir[4096];
    snprintf(dir, sizeof dir, "%s", path);
    for (char *p = dir + 1; *p; p++) {
        if (*p != '/') {
            continue;
        }
        *p = '\0';
        if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
            snprintf(err->message, sizeof err->message, "cannot make the directory '%.400s': %s",
                     dir, strerror(errno));
            return false;
        }
        *p = '/';
    }
    return true;
}

/* Write the image in hand and pass its record on. */
static void write_image(batch_writer *w)
{
    sr_io_error err = { { 0 } };
    double t0 = now_ms();
    bool ok = batch_make_parents(w->rec.output, &err) &&
              cli_write_image(w->rec.output, w->width, w->height, w->pixels, &w->opt, &err) ==
                  SR_OK;
    w->rec.encode_ms = now_ms() - t0;
    w->rec.status = ok ? "ok" : "failed";
    w->done(w->user, &w->rec, ok ? NULL : err.message);
}

static void *writer_main(void *arg)
{
    batch_writer *w = arg;
    pthread_mutex_lock(&w->lock);
    for (;;) {
        while (!w->full && !w->stop) {
            pthread_cond_wait(&w->wake, &w->lock);
        }
        if (!w->full) {
            break;
        }
        pthread_mutex_unlock(&w->lock);
        write_image(w);
        pthread_mutex_lock(&w->lock);
        w->full = false;
        pthread_cond_broadcast(&w->wake);
    }
    pthread_mutex_unlock(&w->lock);
    return NULL;
}

void batch_writer_start(batch_writer *w, batch_done_fn done, void *user)
{
    *w = (batch_writer){ .done = done, .user = user };
    pthread_mutex_init(&w->lock, NULL);
    pthread_cond_init(&w->wake, NULL);
    w->threaded = pthread_create(&w->thread, NULL, writer_main, w) == 0;
}

void batch_writer_wait(batch_writer *w)
{
    pthread_mutex_lock(&w->lock);
    while (w->full) {
        pthread_cond_wait(&w->wake, &w->lock);
    }
    pthread_mutex_unlock(&w->lock);
}

bool batch_writer_put(batch_writer *w, const batch_record *rec, int width, int height,
                      const uint8_t *rgba, const cli_image_options *opt)
{
    batch_writer_wait(w);
    size_t bytes = 4 * (size_t)width * (size_t)height;
    if (bytes > w->capacity) {
        uint8_t *grown = realloc(w->pixels, bytes);
        if (!grown) {
            return false;
        }
        w->pixels = grown;
        w->capacity = bytes;
    }
    memcpy(w->pixels, rgba, bytes);
    w->rec = *rec;
    snprintf(w->output, sizeof w->output, "%s", rec->output);
    w->rec.output = w->output;
    w->width = width;
    w->height = height;
    w->opt = *opt;
    w->opt.context = NULL;   /* the render job's context is not ours to use */
    w->opt.inputs = NULL;    /* the batch checked them; the job's change with the next model */
    if (!w->threaded) {
        write_image(w);
        return true;
    }
    pthread_mutex_lock(&w->lock);
    w->full = true;
    pthread_cond_broadcast(&w->wake);
    pthread_mutex_unlock(&w->lock);
    return true;
}

void batch_writer_stop(batch_writer *w)
{
    if (w->threaded) {
        pthread_mutex_lock(&w->lock);
        w->stop = true;
        pthread_cond_broadcast(&w->wake);
        pthread_mutex_unlock(&w->lock);
        pthread_join(w->thread, NULL);
    }
    pthread_cond_destroy(&w->wake);
    pthread_mutex_destroy(&w->lock);
    free(w->pixels);
    w->pixels = NULL;
}
