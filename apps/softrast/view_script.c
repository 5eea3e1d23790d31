/* view_script.c - scripted input for `softrast view --events FILE`, so tests
 * (and demos) can drive the viewer: each command becomes SDL events pushed
 * onto SDL's queue, handled exactly like a real mouse and keyboard.
 *
 *   drag left|right|middle X0 Y0 X1 Y1 [STEPS]   press, move, release
 *   wheel N                                      N notches (positive: closer)
 *   key [shift+]NAME                             press and release (SDL key name)
 *   resize W H                                   resize the window
 *   frames N                                     let N frames be drawn first
 *   screenshot FILE                              write the next frame as PNG
 *   quit                                         (after a screenshot's frame)
 *
 * Blank lines are ignored, and so is a # at the start of a line or after
 * a space or tab, with the rest of its line (a comment). */
#ifdef SR_HAVE_VIEWER
#include "cli.h"
#include "view_sdl.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { CMD_DRAG, CMD_WHEEL, CMD_KEY, CMD_RESIZE, CMD_FRAMES, CMD_SCREENSHOT, CMD_QUIT };

typedef struct command {
    int kind;
    int a[6];                 /* drag: button x0 y0 x1 y1 steps; wheel: n; resize: w h; frames: n */
    SDL_Keycode key;
    Uint16 mod;
    char *path;
} command;

struct view_script {
    command *cmds;
    int count, next;
};

void view_script_free(view_script *s)
{
    if (!s) {
        return;
    }
    for (int i = 0; i < s->count; i++) {
        free(s->cmds[i].path);
    }
    free(s->cmds);
    free(s);
}

static bool ints(const char *s, int n, int *out, int lo, int hi)
{
    for (int i = 0; i < n; i++) {
        char *end;
        errno = 0;
        long v = strtol(s, &end, 10);
        if (errno || end == s || v < lo || v > hi) {
            return false;
        }
        out[i] = (int)v;
        s = end;
    }
    while (*s == ' ' || *s == '\t') {
        s++;
    }
    return *s == 0;
}

static bool parse_line(char *line, command *c, const char **why)
{
    char *sp = line + strcspn(line, " \t");
    char *rest = *sp ? sp + 1 + strspn(sp + 1, " \t") : sp;
    *sp = 0;
    memset(c, 0, sizeof *c);
    if (strcmp(line, "drag") == 0) {
        c->kind = CMD_DRAG;
        char button[16];
        int n = 0;
        if (sscanf(rest, "%15s %n", button, &n) != 1) {
            *why = "drag needs BUTTON X0 Y0 X1 Y1 [STEPS]";
            return false;
        }
        c->a[0] = strcmp(button, "left") == 0 ? SDL_BUTTON_LEFT
                : strcmp(button, "right") == 0 ? SDL_BUTTON_RIGHT
                : strcmp(button, "middle") == 0 ? SDL_BUTTON_MIDDLE : 0;
        c->a[5] = 8;
        if (!c->a[0]) {
            *why = "drag: the button is left, right or middle";
            return false;
        }
        if (!ints(rest + n, 4, c->a + 1, -100000, 100000) &&
            !ints(rest + n, 5, c->a + 1, -100000, 100000)) {
            *why = "drag needs BUTTON X0 Y0 X1 Y1 [STEPS] (whole numbers)";
            return false;
        }
        if (c->a[5] < 1 || c->a[5] > 1000) {
            *why = "drag: STEPS is 1..1000";
            return false;
        }
        return true;
    }
    if (strcmp(line, "wheel") == 0) {
        c->kind = CMD_WHEEL;
        *why = "wheel needs N, a whole number of notches";
        return ints(rest, 1, c->a, -1000, 1000);
    }
    if (strcmp(line, "resize") == 0) {
        c->kind = CMD_RESIZE;
        *why = "resize needs W H, each 1..8192";
        return ints(rest, 2, c->a, 1, SR_MAX_FRAMEBUFFER_SIZE);
    }
    if (strcmp(line, "frames") == 0) {
        c->kind = CMD_FRAMES;
        *why = "frames needs N, 1..100000";
        return ints(rest, 1, c->a, 1, 100000);
    }
    if (strcmp(line, "key") == 0) {
        c->kind = CMD_KEY;
        if (strncmp(rest, "shift+", 6) == 0) {
            c->mod = KMOD_LSHIFT;
            rest += 6;
        }
        rest[strcspn(rest, " \t")] = 0;
        c->key = SDL_GetKeyFromName(rest);
        *why = "key needs an SDL key name (A, Return, Tab, Escape, ...)";
        return c->key != SDLK_UNKNOWN;
    }
    if (strcmp(line, "screenshot") == 0) {
        c->kind = CMD_SCREENSHOT;
        size_t n = strlen(rest);
        while (n && (rest[n - 1] == ' ' || rest[n - 1] == '\t')) {
            rest[--n] = 0;
        }
        *why = n ? "out of memory" : "screenshot needs FILE";
        c->path = n ? strdup(rest) : NULL;
        return c->path != NULL;
    }
    if (strcmp(line, "quit") == 0) {
        c->kind = CMD_QUIT;
        *why = "quit takes nothing";
        return *rest == 0;
    }
    *why = "unknown command (drag, wheel, key, resize, frames, screenshot, quit)";
    return false;
}

int view_script_load(const char *path, view_script **out)
{
    *out = NULL;
    /* Only a regular file: a directory opens and then reads as nothing
     * (an empty script), and opening a FIFO waits for a writer, maybe
     * forever (sr_open_file opens without waiting, then refuses). */
    FILE *f;
    unsigned long long size;
    sr_io_error err;
    if (sr_open_file(path, "an event script", &f, &size, &err) != SR_OK) {
        cli_error("--events: %s", err.message);
        return EXIT_USAGE;
    }
    view_script *s = calloc(1, sizeof *s);
    int cap = 0, lineno = 0;
    char line[4200];
    while (s && fgets(line, sizeof line, f)) {
        lineno++;
        size_t len = strlen(line);
        if (len == sizeof line - 1 && line[len - 1] != '\n' && !feof(f)) {
            /* fgets would hand the rest over as the next line. */
            fprintf(stderr, "%s:%d: line longer than %zu characters\n", path, lineno,
                    sizeof line - 2);
            fclose(f);
            view_script_free(s);
            return EXIT_USAGE;
        }
        line[strcspn(line, "\r\n")] = 0;
        char *p = line + strspn(line, " \t");
        for (char *q = p; *q; q++) {
            if (*q == '#' && (q == p || q[-1] == ' ' || q[-1] == '\t')) {
                *q = 0;   /* a comment: a file name may hold a # elsewhere */
                break;
            }
        }
        if (*p == 0) {
            continue;
        }
        if (s->count == cap) {
            cap = cap ? 2 * cap : 32;
            command *nc = realloc(s->cmds, (size_t)cap * sizeof *nc);
            if (!nc) {
                fclose(f);
                view_script_free(s);
                cli_error("--events: out of memory");
                return EXIT_FAILURE_RUN;
            }
            s->cmds = nc;
        }
        const char *why = "";
        if (!parse_line(p, &s->cmds[s->count], &why)) {
            fprintf(stderr, "%s:%d: %s\n", path, lineno, why);
            fclose(f);
            view_script_free(s);
            return EXIT_USAGE;
        }
        s->count++;
    }
    fclose(f);
    if (!s) {
        cli_error("--events: out of memory");
        view_script_free(s);
        return EXIT_FAILURE_RUN;
    }
    *out = s;
    return -1;
}

static void push_button(SDL_Window *win, Uint32 type, int button, int x, int y)
{
    SDL_Event e = { .type = type };
    e.button.windowID = SDL_GetWindowID(win);
    e.button.button = (Uint8)button;
    e.button.state = type == SDL_MOUSEBUTTONDOWN ? SDL_PRESSED : SDL_RELEASED;
    e.button.clicks = 1;
    e.button.x = x;
    e.button.y = y;
    SDL_PushEvent(&e);
}

static void push_drag(SDL_Window *win, const int *a)
{
    int button = a[0], x0 = a[1], y0 = a[2], x1 = a[3], y1 = a[4], steps = a[5];
    push_button(win, SDL_MOUSEBUTTONDOWN, button, x0, y0);
    int px = x0, py = y0;
    for (int k = 1; k <= steps; k++) {
        int x = x0 + (int)((long long)(x1 - x0) * k / steps);
        int y = y0 + (int)((long long)(y1 - y0) * k / steps);
        SDL_Event e = { .type = SDL_MOUSEMOTION };
        e.motion.windowID = SDL_GetWindowID(win);
        e.motion.state = SDL_BUTTON(button);
        e.motion.x = x;
        e.motion.y = y;
        e.motion.xrel = x - px;
        e.motion.yrel = y - py;
        SDL_PushEvent(&e);
        px = x;
        py = y;
    }
    push_button(win, SDL_MOUSEBUTTONUP, button, x1, y1);
}

static void push_key(SDL_Window *win, SDL_Keycode key, Uint16 mod)
{
    for (int up = 0; up < 2; up++) {
        SDL_Event e = { .type = up ? SDL_KEYUP : SDL_KEYDOWN };
        e.key.windowID = SDL_GetWindowID(win);
        e.key.state = up ? SDL_RELEASED : SDL_PRESSED;
        e.key.keysym.sym = key;
        e.key.keysym.scancode = SDL_GetScancodeFromKey(key);
        e.key.keysym.mod = mod;
        SDL_PushEvent(&e);
    }
}

int view_script_advance(view_script *s, SDL_Window *win, Uint32 screenshot_event)
{
    bool shot = false;     /* a screenshot asked for in this round */
    while (s->next < s->count) {
        command *c = &s->cmds[s->next++];
        switch (c->kind) {
        case CMD_DRAG:
            push_drag(win, c->a);
            break;
        case CMD_WHEEL: {
            SDL_Event e = { .type = SDL_MOUSEWHEEL };
            e.wheel.windowID = SDL_GetWindowID(win);
            e.wheel.y = c->a[0];
            e.wheel.direction = SDL_MOUSEWHEEL_NORMAL;
            SDL_PushEvent(&e);
            break;
        }
        case CMD_KEY:
            push_key(win, c->key, c->mod);
            break;
        case CMD_RESIZE:
            SDL_SetWindowSize(win, c->a[0], c->a[1]);
            break;
        case CMD_FRAMES:
            return c->a[0];
        case CMD_SCREENSHOT: {
            shot = true;
            SDL_Event e = { .type = screenshot_event };
            e.user.data1 = strdup(c->path);
            if (e.user.data1) {
                SDL_PushEvent(&e);
            }
            break;
        }
        case CMD_QUIT: {
            if (shot) {
                /* The screenshot is taken by the next frame, which a quit
                 * handled now would never draw: quit after it. */
                s->next--;
                return 1;
            }
            SDL_Event e = { .type = SDL_QUIT };
            SDL_PushEvent(&e);
            break;
        }
        }
    }
    return 0;
}
#endif /* SR_HAVE_VIEWER */
