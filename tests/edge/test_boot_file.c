/*
 * The host node's boot counter (firmware/edge/boot_file.c): folders made, ids counted up from 1, never
 * the same twice when many processes take one at once, and every unusable file a clear error that
 * names the path and leaves no id handed out.
 */
#define _POSIX_C_SOURCE 200809L

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "boot_file.h"
#include "unity.h"

static char folder[256];
static char path[512];
static char why[512];

void setUp(void)
{
    snprintf(folder, sizeof(folder), "/tmp/tvo_boot_file_test.XXXXXX");
    TEST_ASSERT_NOT_NULL(mkdtemp(folder));
    snprintf(path, sizeof(path), "%s/state/tvo-flat/node-boot-id", folder);
}

void tearDown(void)
{
    char command[600];
    snprintf(command, sizeof(command), "rm -rf '%s'", folder);
    TEST_ASSERT_EQUAL(0, system(command));
}

static void write_file(const char *text)
{
    FILE *f = fopen(path, "w");
    TEST_ASSERT_NOT_NULL(f);
    fputs(text, f);
    fclose(f);
}

static void read_file(char *out, size_t size)
{
    FILE *f = fopen(path, "r");
    TEST_ASSERT_NOT_NULL(f);
    const size_t n = fread(out, 1u, size - 1u, f);
    out[n] = '\0';
    fclose(f);
}

static void test_the_first_start_makes_the_folders_and_counts_from_one(void)
{
    int64_t id = -1;
    TEST_ASSERT_EQUAL(0, tvo_boot_file_next(path, &id, why, sizeof(why)));
    TEST_ASSERT_EQUAL_INT64(1, id);
    TEST_ASSERT_EQUAL(0, tvo_boot_file_next(path, &id, why, sizeof(why)));
    TEST_ASSERT_EQUAL_INT64(2, id);
    char text[32];
    read_file(text, sizeof(text));
    TEST_ASSERT_EQUAL_STRING("2\n", text);
    struct stat st;
    TEST_ASSERT_EQUAL(0, stat(path, &st));
    TEST_ASSERT_EQUAL_HEX32(0600u, st.st_mode & 0777u);
    char parent[512];
    snprintf(parent, sizeof(parent), "%s/state/tvo-flat", folder);
    TEST_ASSERT_EQUAL(0, stat(parent, &st));
    TEST_ASSERT_EQUAL_HEX32(0700u, st.st_mode & 0777u);
    /* An empty file (made by hand) counts as 0; a number written by hand is continued. */
    write_file("");
    TEST_ASSERT_EQUAL(0, tvo_boot_file_next(path, &id, why, sizeof(why)));
    TEST_ASSERT_EQUAL_INT64(1, id);
    write_file("41");
    TEST_ASSERT_EQUAL(0, tvo_boot_file_next(path, &id, why, sizeof(why)));
    TEST_ASSERT_EQUAL_INT64(42, id);
}

/* Many nodes starting at once on one machine share the file and never get the same id. */
static void test_processes_starting_at_once_get_distinct_ids(void)
{
    enum { PROCESSES = 24 };
    int64_t first = 0;
    TEST_ASSERT_EQUAL(0, tvo_boot_file_next(path, &first, why, sizeof(why)));
    int pipes[2];
    TEST_ASSERT_EQUAL(0, pipe(pipes));
    for (int p = 0; p < PROCESSES; ++p) {
        const pid_t child = fork();
        TEST_ASSERT_TRUE(child >= 0);
        if (child == 0) {
            int64_t id = 0;
            char child_why[256];
            if (tvo_boot_file_next(path, &id, child_why, sizeof(child_why)) != 0) {
                id = 0;
            }
            _exit(write(pipes[1], &id, sizeof(id)) == (ssize_t)sizeof(id) ? 0 : 1);
        }
    }
    close(pipes[1]);
    int seen[PROCESSES + 2] = {0};
    for (int p = 0; p < PROCESSES; ++p) {
        int64_t id = 0;
        TEST_ASSERT_EQUAL(sizeof(id), read(pipes[0], &id, sizeof(id)));
        TEST_ASSERT_TRUE(id >= first + 1 && id <= first + PROCESSES);
        seen[id - first]++;
    }
    close(pipes[0]);
    for (int p = 0; p < PROCESSES; ++p) {
        int status = 0;
        TEST_ASSERT_TRUE(wait(&status) > 0);
        TEST_ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    }
    for (int k = 1; k <= PROCESSES; ++k) {
        TEST_ASSERT_EQUAL_INT(1, seen[k]);
    }
}

/* A file that is not a boot id is an error naming the path; the file is left for a person to fix. */
static void expect_refused(const char *contents, const char *phrase)
{
    write_file(contents);
    int64_t id = -1;
    why[0] = '\0';
    TEST_ASSERT_EQUAL(-1, tvo_boot_file_next(path, &id, why, sizeof(why)));
    TEST_ASSERT_EQUAL_INT64(0, id);
    TEST_ASSERT_NOT_NULL(strstr(why, path));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(why, phrase), why);
    char text[64];
    read_file(text, sizeof(text));
    TEST_ASSERT_EQUAL_STRING(contents, text);
}

static void test_unusable_files_are_clear_errors(void)
{
    int64_t id = 0;
    TEST_ASSERT_EQUAL(0, tvo_boot_file_next(path, &id, why, sizeof(why))); /* makes the folders */
    expect_refused("twelve\n", "found 'twelve?'");
    expect_refused("-3\n", "expected the last boot id");
    expect_refused("12 \n", "expected the last boot id");
    expect_refused("99999999999999999999\n", "expected the last boot id");
    expect_refused("8388607\n", "every boot id up to 8388607 is used");
    /* A folder in the way, or no path. */
    char blocked[600];
    snprintf(blocked, sizeof(blocked), "%s/node-boot-id/x", path);
    TEST_ASSERT_EQUAL(-1, tvo_boot_file_next(blocked, &id, why, sizeof(why)));
    TEST_ASSERT_NOT_NULL(strstr(why, blocked));
    TEST_ASSERT_EQUAL(-1, tvo_boot_file_next(folder, &id, why, sizeof(why)));
    TEST_ASSERT_EQUAL(-1, tvo_boot_file_next(NULL, &id, why, sizeof(why)));
    TEST_ASSERT_EQUAL(-1, tvo_boot_file_next("", &id, why, sizeof(why)));
}

static void test_the_default_path_follows_xdg_then_home(void)
{
    char out[512];
    TEST_ASSERT_EQUAL(0, setenv("XDG_STATE_HOME", "/srv/state", 1));
    TEST_ASSERT_EQUAL(0, tvo_boot_file_default_path(out, sizeof(out), why, sizeof(why)));
    TEST_ASSERT_EQUAL_STRING("/srv/state/tvo-flat/node-boot-id", out);
    TEST_ASSERT_EQUAL(0, setenv("XDG_STATE_HOME", "relative", 1)); /* the XDG spec: ignored unless absolute */
    TEST_ASSERT_EQUAL(0, setenv("HOME", "/home/robot", 1));
    TEST_ASSERT_EQUAL(0, tvo_boot_file_default_path(out, sizeof(out), why, sizeof(why)));
    TEST_ASSERT_EQUAL_STRING("/home/robot/.local/state/tvo-flat/node-boot-id", out);
    TEST_ASSERT_EQUAL(0, unsetenv("XDG_STATE_HOME"));
    TEST_ASSERT_EQUAL(0, unsetenv("HOME"));
    TEST_ASSERT_EQUAL(-1, tvo_boot_file_default_path(out, sizeof(out), why, sizeof(why)));
    TEST_ASSERT_NOT_NULL(strstr(why, "HOME"));
    TEST_ASSERT_EQUAL(0, setenv("HOME", "/home/robot", 1));
    TEST_ASSERT_EQUAL(-1, tvo_boot_file_default_path(out, 10u, why, sizeof(why))); /* does not fit */
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_the_first_start_makes_the_folders_and_counts_from_one);
    RUN_TEST(test_processes_starting_at_once_get_distinct_ids);
    RUN_TEST(test_unusable_files_are_clear_errors);
    RUN_TEST(test_the_default_path_follows_xdg_then_home);
    return UNITY_END();
}
