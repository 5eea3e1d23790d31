/* cli.h - shared pieces of the softrast command-line tool: the
 * subcommands, and parsers for option values that print one clear line
 * naming the option when a value is bad. */
#ifndef SR_CLI_H
#define SR_CLI_H

#include "softrast.h"
#include "softrast_io.h"

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

/* Exit statuses: 2 for bad usage or bad input files, 1 when the work
 * itself fails (out of memory, the output cannot be written). */
enum { EXIT_OK = 0, EXIT_FAILURE_RUN = 1, EXIT_USAGE = 2 };

int cmd_render(int argc, char **argv);
int cmd_demo(int argc, char **argv);
int cmd_thumbnail(int argc, char **argv); /* thumbnail.c: a render for file managers */
int cmd_info(int argc, char **argv);      /* info.c: what a model file holds */
/* batch.c: `softrast render` with several models, a directory, a list or
 * the batch options; -1 when the arguments ask for one plain render. */
int batch_render(int argc, char **argv);
int cmd_svg(int argc, char **argv);   /* svg.c; needs expat */
int cmd_explain(int argc, char **argv); /* explain.c: an algorithm step by step */
int cmd_view(int argc, char **argv);  /* view.c; needs SDL2 and FreeType */

/* The files a command reads (inputs.c), so that no output replaces one:
 * compared by device and inode, so other names and links count too. */
typedef struct cli_input cli_input;
typedef struct cli_inputs {
    cli_input *items;
    size_t count, cap;
    bool incomplete;    /* out of memory once: every output is refused */
} cli_inputs;

/* Record `path` as an input of `kind` ("model", "texture", ...: a string
 * that outlives `in`); a path that does not exist is skipped.  false (and
 * in->incomplete) when out of memory. */
bool cli_inputs_add(cli_inputs *in, const char *path, const char *kind);
/* cli_inputs_add where the file is read, counting the reads: --verbose
 * reports them (cli_inputs_report), so that a tool test can see a file
 * read once. */
bool cli_inputs_read(cli_inputs *in, const char *path, const char *kind);
/* "softrast: read PATH (KIND) N times" to stderr for each file read. */
void cli_inputs_report(const cli_inputs *in);
/* Whether `output` is one of the inputs (in may be NULL); if so `why`
 * says "'OUT' is the KIND being read (PATH); choose another output file". */
bool cli_output_is_input(const cli_inputs *in, const char *output, char *why, size_t why_size);
/* The same as a check: false after printing "softrast: OPT: why". */
bool cli_check_output(const cli_inputs *in, const char *opt, const char *output);
void cli_inputs_free(cli_inputs *in);
/* Whether two outputs of one run are the same file, written or not yet
 * (one would replace the other). */
bool cli_same_output(const char *a, const char *b);

/* Whether `output` may name an output file: "" (which the library would
 * refuse later, without the option's name), "-" (standard output, where
 * no image is written) and "--" (the end of the options, taken as the
 * option's value by the getopt rule) are refused after one line naming
 * opt; any other name, one starting with '-' too, is a file's. */
bool cli_check_output_name(const char *opt, const char *output);

/* Frame memory (memory_limit.c): -1 when `need` bytes fit the memory
 * limit (sr_query_memory_limit: SR_MEMORY_LIMIT, else the physical memory
 * or less under a ulimit); else EXIT_USAGE after one line "WHAT needs
 * about N GiB of frame memory, more than SR_MEMORY_LIMIT=M allows: LOWER"
 * (lower says which options make it smaller), or naming a malformed
 * SR_MEMORY_LIMIT. */
int cli_check_memory(const char *what, uint64_t need, const char *lower);

/* Image files (image_out.c writes them, image_name.c checks their
 * names): a JPEG when the name ends in .jpg or .jpeg (any case), else a
 * PNG. */
typedef struct cli_image_options {
    int png_level;         /* -1: the library's default; 0: stored; 1..9 */
    int jpeg_quality;      /* 0: the library's default; 1..100 */
    bool keep_alpha;       /* PNG only: write RGBA rather than RGB */
    bool premultiplied;    /* the colors are multiplied by alpha (a render over a
                            * transparent background): written straight */
    sr_context *context;   /* PNG only: compress on its threads (may be NULL) */
    const cli_inputs *inputs; /* never written over: SR_INVALID_ARG (may be NULL) */
} cli_image_options;

bool cli_is_jpeg_name(const char *path);
/* Whether path names an image cli_write_image writes: ending in .png,
 * .jpg or .jpeg (any case; .png only when !jpeg_ok), or with no
 * extension (a PNG).  Another extension ("x.bmp") is refused after one
 * line naming opt rather than given PNG bytes under a name that says
 * otherwise. */
bool cli_check_image_name(const char *opt, const char *path, bool jpeg_ok);
/* Make the directories above `path` (mkdir -p of its dirname); false with
 * the reason in err (make_parents.c). */
bool cli_make_parents(const char *path, sr_io_error *err);
/* PNG and WebP store straight alpha: a render over a transparent
 * background has its edges' colors multiplied by their coverage (the
 * resolve averages the model's samples with transparent black), so this
 * divides it out.  A malloc'd copy, or NULL. */
uint8_t *cli_straight_alpha(const uint8_t *rgba, size_t pixels);
sr_result cli_write_image(const char *path, int width, int height, const uint8_t *rgba,
                          const cli_image_options *opt, sr_io_error *err);

/* Control bytes (a newline, an escape sequence) in text, which may quote
 * a file name or an argument, as '?': a message stays one line and cannot
 * drive the terminal. */
void cli_one_line(char *text);
/* Why a library call just failed with r: the thread's sr_last_error,
 * which names the argument, or r's text when it left none (clear it with
 * sr_set_last_error(NULL) before the call, so that an older one cannot
 * answer). */
const char *cli_why(sr_result r);
/* Print "softrast: ..." to stderr (one line). */
void cli_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* Print one line to stderr as it is (a reader's "FILE:LINE: why"). */
void cli_message(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* Hold the messages of cli_error and cli_message in buf (joined by "; ",
 * without the "softrast: " prefix) instead of printing them, until
 * cli_capture(NULL, 0): a batch reports one line per failed input.  Each
 * thread holds its own messages. */
void cli_capture(char *buf, size_t size);

/* How a command reads one argument, by POSIX's utility syntax: an
 * operand (a file, a name) does not start with '-', or is "-" alone, or
 * comes after "--"; the first "--" ends the options and is itself
 * dropped; the rest are options.  *ended (false before the first
 * argument) remembers the "--". */
typedef enum cli_arg_kind { CLI_ARG_OPTION, CLI_ARG_OPERAND, CLI_ARG_END } cli_arg_kind;
cli_arg_kind cli_arg(const char *arg, bool *ended);

/* An option argument split as getopt_long reads it: "--name=value" into
 * its name and value (a long option only), else name = arg and no value,
 * so that every command takes "--name value" and "--name=value" alike. */
typedef struct cli_opt {
    char name[64];
    const char *value;     /* after '=', or NULL */
} cli_opt;
void cli_split_option(const char *arg, cli_opt *o);
/* The option's value: its "=value", else the next argument (*i moves on
 * to it), whatever it looks like; NULL after one line "NAME: missing
 * value". */
const char *cli_option_value(const cli_opt *o, int argc, char **argv, int *i);
/* An option that takes no value: false after one line "NAME: takes no
 * value" when it was given one. */
bool cli_option_flag(const cli_opt *o);
/* -h or --help: EXIT_OK after help(stdout), or EXIT_USAGE after one line
 * for --help=VALUE; -1 for another option. */
int cli_help_option(const cli_opt *o, void (*help)(FILE *));

/* Parsers: return false after printing "softrast render: OPTION: why". */
bool parse_int(const char *opt, const char *s, int lo, int hi, int *out);
bool parse_float(const char *opt, const char *s, float lo, float hi, float *out);
/* WxH with each side from 1 to the framebuffer's limit, or to max. */
bool parse_size(const char *opt, const char *s, int *w, int *h);
bool parse_size_max(const char *opt, const char *s, int max, int *w, int *h);
bool parse_vec3(const char *opt, const char *s, sr_vec3 *out);
bool parse_color(const char *opt, const char *s, sr_vec3 *out);
/* One of `names` (NULL-terminated); *out = its index. */
bool parse_choice(const char *opt, const char *s, const char *const *names, int *out);

/* Comma-separated key=value lists, e.g. "eye=1,2,3,target=0,0,0".  Values
 * may contain commas; a new key starts at a token that contains '='.
 * Calls fn(key, value) for each; stops and returns false if fn does. */
typedef bool (*kv_fn)(void *user, const char *opt, const char *key, const char *value);
bool parse_kv_list(const char *opt, const char *s, kv_fn fn, void *user);

#endif
