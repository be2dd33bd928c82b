/* A DDS program of another vendor on ROS 2's names (issue 45, docs/ros2.md): Cyclone DDS, its
 * types compiled by idlc from `brickyard ros2 idl`, no Brickyard code. It reads or writes a graph
 * whose transport.naming is "ros2", as a ROS 2 node with rmw_cyclonedds would.
 *   read DOMAIN SECONDS    every sample of rt/brickyard/estimator/estimate
 *                          (LocalizationEstimate) and rt/brickyard/manager/command (ControlCommand)
 *                          for SECONDS, a JSON line each on stdout; exit 1 when none came.
 *   write DOMAIN COUNT HZ  COUNT samples of rt/brickyard/src/out (Scalar), values 1, 2, ..., at HZ,
 *                          once a reader has matched (within 20 s, else exit 1), then waits for
 *                          them to be acknowledged (exit 1 when they are not within 10 s).
 * Discovery: CYCLONEDDS_URI, set by the test (loopback only, unicast peers, no multicast). */
#include "brickyard_msgs_dds.h"

#include <dds/dds.h>

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define ESTIMATE_TOPIC "rt/brickyard/estimator/estimate"
#define COMMAND_TOPIC "rt/brickyard/manager/command"
#define SOURCE_TOPIC "rt/brickyard/src/out"

static void print_header(const brickyard_msgs_msg_dds__Header_* h) {
  printf("\"header\":{\"stamp_ns\":%" PRId64 ",\"seq\":%" PRIu32 ",\"frame_id\":\"%s\"}", h->stamp_ns, h->seq, h->frame_id ? h->frame_id : "");
}

static void print_estimate(const brickyard_msgs_msg_dds__LocalizationEstimate_* m) {
  printf("{\"topic\":\"estimator.estimate\",\"msg\":{");
  print_header(&m->header);
  printf(",\"x\":%.17g,\"y\":%.17g,\"yaw\":%.17g,\"speed\":%.17g,\"yaw_rate\":%.17g,\"covariance\":[", m->x, m->y, m->yaw, m->speed, m->yaw_rate);
  for (int i = 0; i < 9; ++i) printf("%s%.17g", i ? "," : "", m->covariance[i]);
  printf("],\"update_case\":%u,\"delta\":[", m->update_case);
  for (uint32_t i = 0; i < m->delta._length; ++i) printf("%s%.17g", i ? "," : "", m->delta._buffer[i]);
  printf("],\"status\":%u}}\n", m->status);
}

static void print_command(const brickyard_msgs_msg_dds__ControlCommand_* m) {
  printf("{\"topic\":\"manager.command\",\"msg\":{");
  print_header(&m->header);
  printf(",\"steer\":%.17g,\"throttle\":%.17g,\"brake\":%.17g,\"target_speed\":%.17g,\"source\":\"%s\"}}\n", m->steer, m->throttle, m->brake,
         m->target_speed, m->source ? m->source : "");
}

/* Reliable, volatile, every sample kept: what a ROS 2 subscription asks, with a deep queue. */
static dds_qos_t* reader_qos(void) {
  dds_qos_t* q = dds_create_qos();
  dds_qset_reliability(q, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
  dds_qset_durability(q, DDS_DURABILITY_VOLATILE);
  dds_qset_history(q, DDS_HISTORY_KEEP_ALL, 0);
  return q;
}

/* Takes whatever `reader` holds, printing each valid sample; the count taken. */
static long take_all(dds_entity_t reader, int estimate) {
  void* samples[64] = {0};
  dds_sample_info_t infos[64];
  long n = 0;
  for (;;) {
    const dds_return_t got = dds_take(reader, samples, infos, 64, 64);
    if (got <= 0) break;
    for (int i = 0; i < got; ++i) {
      if (!infos[i].valid_data) continue;
      if (estimate) print_estimate(samples[i]);
      else print_command(samples[i]);
      ++n;
    }
    dds_return_loan(reader, samples, got);
  }
  return n;
}

static int read_topics(dds_entity_t participant, double seconds) {
  dds_qos_t* q = reader_qos();
  const dds_entity_t est_topic = dds_create_topic(participant, &brickyard_msgs_msg_dds__LocalizationEstimate__desc, ESTIMATE_TOPIC, NULL, NULL);
  const dds_entity_t cmd_topic = dds_create_topic(participant, &brickyard_msgs_msg_dds__ControlCommand__desc, COMMAND_TOPIC, NULL, NULL);
  const dds_entity_t est = dds_create_reader(participant, est_topic, q, NULL);
  const dds_entity_t cmd = dds_create_reader(participant, cmd_topic, q, NULL);
  dds_delete_qos(q);
  if (est < 0 || cmd < 0) return fprintf(stderr, "cyclone_peer: cannot create the readers: %s\n", dds_strretcode(est < 0 ? est : cmd)), 1;
  long estimates = 0, commands = 0;
  const dds_time_t end = dds_time() + (dds_time_t)(seconds * 1e9);
  while (dds_time() < end) {
    estimates += take_all(est, 1);
    commands += take_all(cmd, 0);
    dds_sleepfor(DDS_MSECS(5));
  }
  fflush(stdout);
  fprintf(stderr, "cyclone_peer: read %ld estimates, %ld commands\n", estimates, commands);
  return estimates > 0 && commands > 0 ? 0 : 1;
}

static int wait_matched(dds_entity_t writer, double seconds) {
  const dds_time_t end = dds_time() + (dds_time_t)(seconds * 1e9);
  dds_publication_matched_status_t st;
  while (dds_time() < end) {
    if (dds_get_publication_matched_status(writer, &st) == DDS_RETCODE_OK && st.current_count > 0) return 1;
    dds_sleepfor(DDS_MSECS(10));
  }
  return 0;
}

static int write_source(dds_entity_t participant, long count, double hz) {
  dds_qos_t* q = dds_create_qos();
  dds_qset_reliability(q, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
  dds_qset_history(q, DDS_HISTORY_KEEP_ALL, 0);
  const dds_entity_t topic = dds_create_topic(participant, &brickyard_msgs_msg_dds__Scalar__desc, SOURCE_TOPIC, NULL, NULL);
  const dds_entity_t writer = dds_create_writer(participant, topic, q, NULL);
  dds_delete_qos(q);
  if (writer < 0) return fprintf(stderr, "cyclone_peer: cannot create the writer: %s\n", dds_strretcode(writer)), 1;
  if (!wait_matched(writer, 20)) return fprintf(stderr, "cyclone_peer: no reader of %s matched within 20 s\n", SOURCE_TOPIC), 1;
  char frame[] = "cyclone_peer";
  for (long k = 0; k < count; ++k) {
    brickyard_msgs_msg_dds__Scalar_ s;
    memset(&s, 0, sizeof s);
    s.header.stamp_ns = dds_time();
    s.header.seq = (uint32_t)k;
    s.header.frame_id = frame;
    s.value = (double)(k + 1);
    const dds_return_t rc = dds_write(writer, &s);
    if (rc != DDS_RETCODE_OK) return fprintf(stderr, "cyclone_peer: write %ld: %s\n", k, dds_strretcode(rc)), 1;
    dds_sleepfor((dds_duration_t)(1e9 / hz));
  }
  if (dds_wait_for_acks(writer, DDS_SECS(10)) != DDS_RETCODE_OK) return fprintf(stderr, "cyclone_peer: the samples were not acknowledged within 10 s\n"), 1;
  fprintf(stderr, "cyclone_peer: wrote %ld samples, acknowledged\n", count);
  return 0;
}

int main(int argc, char** argv) {
  if (argc != 4 && argc != 5) return fprintf(stderr, "usage: cyclone_peer read DOMAIN SECONDS | write DOMAIN COUNT HZ\n"), 2;
  const int reading = strcmp(argv[1], "read") == 0;
  if (!reading && (strcmp(argv[1], "write") != 0 || argc != 5)) return fprintf(stderr, "cyclone_peer: %s: expected read or write\n", argv[1]), 2;
  /* Named as the graph's process it stands for (src's, "peer"): a graph takes a wire's samples only
   * from its writer's process, by the participant's name (a filter without security). */
  dds_qos_t* named = dds_create_qos();
  dds_qset_entity_name(named, "brickyard:peer");
  const dds_entity_t participant = dds_create_participant((dds_domainid_t)atoi(argv[2]), named, NULL);
  dds_delete_qos(named);
  if (participant < 0) return fprintf(stderr, "cyclone_peer: cannot create a participant: %s\n", dds_strretcode(participant)), 1;
  const int rc = reading ? read_topics(participant, atof(argv[3])) : write_source(participant, atol(argv[3]), atof(argv[4]));
  dds_delete(participant);
  return rc;
}
