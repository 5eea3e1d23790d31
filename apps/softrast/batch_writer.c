/* batch_writer.c - a batch's image files, written on threads of their
 * own: while they compress images and wait for the disk to take them
 * (each output is fsync'd before it is renamed into place), the batch
 * draws the next input.  It holds up to one image a thread and one more,
 * each its own copy of the pixels, so the framebuffer can be drawn again
 * at once and one slow fsync does not stop the drawing; several threads
 * write side by side, and the images are reported in the order they
 * came.  Each compresses on its own thread: the render job's context is
 * busy drawing. */
#include "batch_writer.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

/* Write an image in hand (its record's status and encode_ms set). */
static void write_image(batch_image *im)
{
    im->err = (sr_io_error){ { 0 } };
    double t0 = now_ms();
    bool ok = cli_make_parents(im->rec.output, &im->err) &&
              cli_write_image(im->rec.output, im->width, im->height, im->pixels, &im->opt,
                              &im->err) == SR_OK;
    im->rec.encode_ms = now_ms() - t0;
    im->rec.status = ok ? "ok" : "failed";
    im->message = ok ? NULL : im->err.message;
}

/* Report the written images at the front of the ring, in order, by one
 * thread at a time; called and returns with the lock held. */
static void report_written(batch_writer *w)
{
    if (w->reporting) {
        return;   /* the thread reporting will come to them */
    }
    w->reporting = true;
    while (w->count > 0 && w->images[w->first].written) {
        batch_image *im = &w->images[w->first];
        pthread_mutex_unlock(&w->lock);
        w->done(w->user, &im->rec, im->message);
        pthread_mutex_lock(&w->lock);
        im->written = false;
        w->held -= im->bytes;
        w->first = (w->first + 1) % w->depth;
        w->count--;
        w->claimed--;
        pthread_cond_broadcast(&w->wake);
    }
    w->reporting = false;
}

/* Each thread takes the oldest image no thread has taken, writes it
 * outside the lock, and reports what is written at the front: the slot
 * stays in hand (count) until it is reported, so the batch never fills
 * it meanwhile. */
static void *writer_main(void *arg)
{
    batch_writer *w = arg;
    pthread_mutex_lock(&w->lock);
    for (;;) {
        while (w->claimed == w->count && !w->stop) {
            pthread_cond_wait(&w->wake, &w->lock);
        }
        if (w->claimed == w->count) {
            break;
        }
        batch_image *im = &w->images[(w->first + w->claimed) % w->depth];
        w->claimed++;
        pthread_mutex_unlock(&w->lock);
        write_image(im);
        pthread_mutex_lock(&w->lock);
        im->written = true;
        report_written(w);
    }
    pthread_mutex_unlock(&w->lock);
    return NULL;
}

void batch_writer_start(batch_writer *w, int threads, batch_done_fn done, void *user)
{
    *w = (batch_writer){ .done = done, .user = user };
    pthread_mutex_init(&w->lock, NULL);
    pthread_cond_init(&w->wake, NULL);
    threads = threads < 1 ? 1 : threads > BATCH_WRITER_MAX_THREADS ? BATCH_WRITER_MAX_THREADS
                                                                    : threads;
    w->depth = threads + 1;
    pthread_mutex_lock(&w->lock);   /* the threads wait for the depth and count */
    for (int i = 0; i < threads; i++) {
        if (pthread_create(&w->threads[w->thread_count], NULL, writer_main, w) == 0) {
            w->thread_count++;
        }
    }
    pthread_mutex_unlock(&w->lock);
}

/* Whether the batch must wait before handing over an image of `bytes`. */
static bool full(const batch_writer *w, size_t bytes)
{
    return w->count >= w->depth ||
           (w->count > 0 && w->held + bytes > BATCH_WRITER_MAX_BYTES);
}

void batch_writer_wait(batch_writer *w)
{
    pthread_mutex_lock(&w->lock);
    while (w->count > 0) {
        pthread_cond_wait(&w->wake, &w->lock);
    }
    pthread_mutex_unlock(&w->lock);
}

bool batch_writer_put(batch_writer *w, const batch_record *rec, int width, int height,
                      const uint8_t *rgba, const cli_image_options *opt)
{
    size_t bytes = 4 * (size_t)width * (size_t)height;
    pthread_mutex_lock(&w->lock);
    while (full(w, bytes)) {
        pthread_cond_wait(&w->wake, &w->lock);
    }
    /* Only this thread adds images, so the free slot stays free. */
    batch_image *im = &w->images[(w->first + w->count) % w->depth];
    pthread_mutex_unlock(&w->lock);
    if (bytes > im->capacity) {
        uint8_t *grown = realloc(im->pixels, bytes);
        if (!grown) {
            return false;
        }
        im->pixels = grown;
        im->capacity = bytes;
    }
    memcpy(im->pixels, rgba, bytes);
    im->bytes = bytes;
    im->rec = *rec;
    snprintf(im->output, sizeof im->output, "%s", rec->output);
    im->rec.output = im->output;
    im->width = width;
    im->height = height;
    im->opt = *opt;
    im->opt.context = NULL;   /* the render job's context is not ours to use */
    im->opt.inputs = NULL;    /* the batch checked them; the job's change with the next model */
    if (w->thread_count == 0) {
        write_image(im);
        w->done(w->user, &im->rec, im->message);
        return true;
    }
    pthread_mutex_lock(&w->lock);
    w->count++;
    w->held += bytes;
    pthread_cond_broadcast(&w->wake);
    pthread_mutex_unlock(&w->lock);
    return true;
}

void batch_writer_stop(batch_writer *w)
{
    pthread_mutex_lock(&w->lock);
    w->stop = true;
    pthread_cond_broadcast(&w->wake);
    pthread_mutex_unlock(&w->lock);
    for (int i = 0; i < w->thread_count; i++) {
        pthread_join(w->threads[i], NULL);
    }
    pthread_cond_destroy(&w->wake);
    pthread_mutex_destroy(&w->lock);
    for (int i = 0; i < BATCH_WRITER_DEPTH; i++) {
        free(w->images[i].pixels);
        w->images[i].pixels = NULL;
    }
}
