/*
 * The keyed node's entry (auth_link.c in front of node.c): a genuine signed session (variant from the
 * first input byte), then a stream of frames that are raw (as a forger sends them), signed with the
 * key, signed and then altered, or signed with a counter already used. Invariants: a frame the link
 * drops publishes nothing and changes neither the sessions nor the link's keys and counters; every
 * frame the node publishes opens with the key and, if a command, decodes within its limits.
 * Record format after the variant byte: mode (1 byte: 0 raw, 1 signed, 2 signed then one bit flipped
 * at the index in the next byte, 3 signed with the last counter again), channel (1 byte), length
 * (2 bytes LE), clock step (1 byte, x 500 us), [flip index,] then `length` bytes of message.
 */
#include "auth_link.h"
#include "fuzz_support.h"

static tvo_node_t node;
static tvo_auth_link_t link;
static tvo_auth_t plant;      /* signs the plant's frames */
static tvo_auth_t listener;   /* opens the node's */
static tvo_lcm_session_t session;
static int published;
static uint8_t frame[16384 + TVO_AUTH_TRAILER_BYTES];
static const uint8_t key[TVO_AUTH_KEY_BYTES] = {7, 1, 8, 2, 8, 1, 8, 2, 8, 4, 5, 9, 0, 4, 5, 2,
                                                3, 5, 3, 6, 0, 2, 8, 7, 4, 7, 1, 3, 5, 2, 6, 6};

static void transport(void *context, int channel, const uint8_t *data, uint32_t length)
{
    (void)context;
    published++;
    size_t message_length = 0u;
    if (tvo_auth_open(&listener, tvo_node_channel_name(channel), data, length, &message_length) != TVO_AUTH_OK) {
        fuzz_fail("the node published a frame that does not open with the key");
    }
    tvo_lcm_command_header_t header;
    (void)fuzz_check_published_command(channel, data, (uint32_t)message_length, &session, &header);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1) {
        return 0;
    }
    published = 0;
    if (tvo_auth_link_init(&link, key, TVO_AUTH_SENDER_NODE, 1u, transport, NULL) != TVO_AUTH_OK ||
        tvo_auth_init(&plant, key, TVO_AUTH_SENDER_PLANT, 1000u) != TVO_AUTH_OK ||
        tvo_auth_init(&listener, key, 99u, 1u) != TVO_AUTH_OK) {
        fuzz_fail("authentication set-up failed");
    }
    if (tvo_node_init(&node, -1, FUZZ_BOOT, tvo_auth_link_publish, &link) != 0) {
        fuzz_fail("node init");
    }
    fuzz_session(&session, data[0]);
    int64_t now = 5000000;
    const int n = tvo_lcm_session_t_encode(frame, 0, 16384, &session);
    size_t length = 0u;
    if (n <= 0 || tvo_auth_sign(&plant, TVO_CHANNEL_SESSION, frame, (size_t)n, sizeof(frame), &length) != TVO_AUTH_OK) {
        fuzz_fail("the reference session could not be signed");
    }
    tvo_auth_link_receive(&link, &node, TVO_NODE_CH_SESSION, frame, (uint32_t)length, now);
    if (tvo_node_session(&node) == NULL) {
        fuzz_fail("the signed reference session was refused");
    }
    size_t i = 1;
    while (i + 5 <= size) {
        const uint8_t mode = data[i] % 4u;
        const int channel = 1 + data[i + 1] % TVO_NODE_CH_LAST;
        size_t message_length = (size_t)data[i + 2] | ((size_t)data[i + 3] << 8);
        now += 500 * (int64_t)data[i + 4];
        i += 5;
        size_t flip = 0u;
        if (mode == 2u && i < size) {
            flip = data[i++];
        }
        if (message_length > size - i) {
            message_length = size - i;
        }
        if (message_length > 16384u) {
            message_length = 16384u;
        }
        memcpy(frame, data + i, message_length);
        i += message_length;
        size_t frame_length = message_length;
        const char *name = tvo_node_channel_name(channel);
        int genuine = 0;
        if (mode != 0u && name != NULL) {
            if (mode == 3u && plant.next_counter > 1000u) {
                plant.next_counter -= 1u; /* the counter of the last frame signed: a replay */
            }
            genuine = tvo_auth_sign(&plant, name, frame, message_length, sizeof(frame), &frame_length) == TVO_AUTH_OK &&
                      mode == 1u;
            if (mode == 2u && frame_length > 0u) {
                frame[flip % frame_length] ^= (uint8_t)(1u << (flip % 8u));
            }
        }
        static tvo_node_session_t slots_before[2];
        static tvo_auth_t auth_before;
        memcpy(slots_before, node.slot, sizeof(slots_before));
        const uint8_t state_before = node.state;
        auth_before = link.auth;
        const int published_before = published;
        link.last_refusal = TVO_AUTH_OK;
        (void)tvo_auth_link_receive(&link, &node, channel, frame, (uint32_t)frame_length, now);
        if (link.last_refusal != TVO_AUTH_OK) {
            if (genuine) {
                fuzz_fail("the link dropped a genuine frame");
            }
            if (published != published_before) {
                fuzz_fail("a dropped frame was answered");
            }
            if (memcmp(&link.auth, &auth_before, TVO_AUTH_STATE_BYTES) != 0) {   /* all but the cipher's scratch */
                fuzz_fail("a dropped frame changed the link's counters");
            }
            if (memcmp(slots_before, node.slot, sizeof(slots_before)) != 0 || state_before != node.state) {
                fuzz_fail("a dropped frame changed the node");
            }
        }
        (void)tvo_node_poll(&node, now);
    }
    return 0;
}
