/*
 * Negative control of the no-allocator check on the main-loop image: board code that allocates
 * (a board_write_command keeping a heap copy of each command). The check must find malloc here.
 */
#include <stdlib.h>

#include "board_io.h"

static tvo_command_t *volatile last_command;   /* volatile: the allocation cannot be optimised away */

void board_write_command(const tvo_command_t *cmd, tvo_status_t status)
{
    tvo_command_t *copy = malloc(sizeof(*copy));
    if (copy != NULL) {
        *copy = *cmd;
    }
    free(last_command);
    last_command = copy;
    (void)status;
}
