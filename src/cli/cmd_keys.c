/* cmd_keys.c - `microcontact keys [SECTION]`: the case-file reference.
 *
 * Without SECTION the generated Markdown (the tail of docs/case-format.md). With SECTION one
 * section of it as plain text for a terminal: no HTML comment, no table syntax, no backticks;
 * each key on a line of its own with its text wrapped, then its unit, default and range. */
#include <ctype.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "case/case.h"
#include "cli/cli.h"
#include "core/alloc.h"

#define WIDTH 78     /* wrap column */
#define NAME_COL 22  /* where a key's text starts */
#define MAX_COLS 8   /* columns of a reference table */
#define CELL_MAX 600 /* longest cell kept (the longest documentation line is about 400) */

/* Print text (len bytes, backticks dropped) word by word from column *col, wrapping at WIDTH to
 * column indent. */
static void wrap(const char *text, size_t len, int *col, int indent)
{
    size_t i = 0;
    while (i < len) {
        while (i < len && isspace((unsigned char)text[i]))
            i++;
        size_t w0 = i;
        int wlen = 0;
        while (i < len && !isspace((unsigned char)text[i]))
            wlen += text[i++] != '`';
        if (wlen == 0)
            continue;
        if (*col > indent && *col + 1 + wlen > WIDTH) {
            printf("\n%*s", indent, "");
            *col = indent;
        } else if (*col > indent) {
            putchar(' ');
            (*col)++;
        }
        for (size_t k = w0; k < i; k++)
            if (text[k] != '`')
                putchar(text[k]);
        *col += wlen;
    }
}

/* Split a Markdown table row "| a | b |" into trimmed cells; returns their number. */
static int split_row(const char *line, size_t len, char cells[][CELL_MAX], int max)
{
    int n = 0;
    size_t i = 1; /* after the leading '|' */
    while (i < len && n < max) {
        size_t j = i;
        while (j < len && line[j] != '|')
            j++;
        if (j >= len)
            break; /* the text after the last '|' */
        size_t a = i, b = j;
        while (a < b && isspace((unsigned char)line[a]))
            a++;
        while (b > a && isspace((unsigned char)line[b - 1]))
            b--;
        size_t m = b - a < CELL_MAX - 1 ? b - a : CELL_MAX - 1;
        memcpy(cells[n], line + a, m);
        cells[n][m] = '\0';
        n++;
        i = j + 1;
    }
    return n;
}

/* One table row: the first cell (the key), the last (its meaning) wrapped beside it, then the
 * cells between as "header: value" (those that are "-" left out). */
static void print_row(char cells[][CELL_MAX], int n, char head[][CELL_MAX])
{
    int col = 2;
    printf("  ");
    for (const char *c = cells[0]; *c; c++)
        if (*c != '`') {
            putchar(*c);
            col++;
        }
    if (n < 2) {
        putchar('\n');
        return;
    }
    if (col >= NAME_COL - 1) {
        printf("\n%*s", NAME_COL, "");
        col = NAME_COL;
    } else {
        col += printf("%*s", NAME_COL - col, "");
    }
    wrap(cells[n - 1], strlen(cells[n - 1]), &col, NAME_COL);
    int first = 1;
    for (int c = 1; c < n - 1; c++) {
        if (!strcmp(cells[c], "-"))
            continue;
        char attr[CELL_MAX + 64];
        snprintf(attr, sizeof attr, "%s: %s%s", head[c], cells[c], c < n - 2 ? ";" : "");
        size_t alen = strlen(attr);
        if (first || (col > NAME_COL && col + 1 + (int)alen > WIDTH)) {
            printf("\n%*s", NAME_COL, ""); /* an attribute starts a line when it fits on one */
            col = NAME_COL;
            first = 0;
        }
        wrap(attr, alen, &col, NAME_COL);
    }
    putchar('\n');
}

/* Print the section that starts at s (its "## " heading line) up to the next heading. */
static void print_section(const char *s)
{
    static char head[MAX_COLS][CELL_MAX], cells[MAX_COLS][CELL_MAX];
    int in_table = 0;
    for (const char *p = s; *p;) {
        size_t len = strcspn(p, "\n");
        if (p != s && strncmp(p, "## ", 3) == 0)
            break;
        if (p == s) {
            printf("%.*s\n", (int)(len - 3), p + 3);
        } else if (len > 0 && p[0] == '|') {
            if (!in_table) {
                split_row(p, len, head, MAX_COLS);
                in_table = 1;
            } else if (strncmp(p, "|---", 4) != 0) {
                print_row(cells, split_row(p, len, cells, MAX_COLS), head);
            }
        } else if (len > 0) {
            int col = 0;
            wrap(p, len, &col, 0);
            putchar('\n');
        } else if (!in_table) {
            putchar('\n');
        }
        if (len == 0)
            in_table = 0;
        p += len + (p[len] == '\n');
    }
}

/* Name of the section heading at h ("## [mesh]" -> "mesh", "## Units" -> "Units"), in buf. */
static void heading_name(const char *h, char *buf, size_t size)
{
    h += 3;
    size_t len = strcspn(h, "\n");
    if (len >= 2 && h[0] == '[' && h[len - 1] == ']') {
        h++;
        len -= 2;
    }
    snprintf(buf, size, "%.*s", (int)len, h);
}

static void list_sections(const char *md, FILE *f)
{
    const char *sep = "";
    for (const char *p = md; (p = strstr(p, "\n## ")) != NULL; p++) {
        char name[64];
        heading_name(p + 1, name, sizeof name);
        fprintf(f, "%s%s", sep, name);
        sep = ", ";
    }
    fputc('\n', f);
}

int mc_cli_keys(int argc, char **argv)
{
    char *md = mc_case_reference_markdown();
    if (!md) {
        fprintf(stderr, "microcontact: out of memory\n");
        return 3;
    }
    int rc = 0;
    if (argc >= 1 && mc_cli_is_help(argv[0])) {
        printf("%s\n\nWithout SECTION: the case-file reference as Markdown (the end of\n"
               "docs/case-format.md). With SECTION: that section as plain text.\nsections: ",
               MC_USAGE_KEYS);
        list_sections(md, stdout);
    } else if (argc > 1 || (argc == 1 && argv[0][0] == '-')) {
        if (argc > 1)
            fprintf(stderr, "microcontact keys: one section at most (got '%s' and '%s')\n",
                    argv[0], argv[1]);
        else
            fprintf(stderr, "microcontact keys: unknown option '%s'\n", argv[0]);
        fprintf(stderr, "%s\n", MC_USAGE_KEYS);
        rc = 2;
    } else if (argc == 0) {
        fputs(md, stdout);
    } else {
        char want[64];
        snprintf(want, sizeof want, "%s", argv[0]);
        size_t n = strlen(want);
        if (n >= 2 && want[0] == '[' && want[n - 1] == ']') {
            memmove(want, want + 1, n - 2);
            want[n - 2] = '\0';
        }
        const char *found = NULL;
        for (const char *p = md; !found && (p = strstr(p, "\n## ")) != NULL; p++) {
            char name[64];
            heading_name(p + 1, name, sizeof name);
            if (strcasecmp(name, want) == 0)
                found = p + 1;
        }
        if (found) {
            print_section(found);
        } else {
            fprintf(stderr, "microcontact keys: unknown section '%s'; sections: ", argv[0]);
            list_sections(md, stderr);
            rc = 2;
        }
    }
    mc_free(md);
    return rc;
}
