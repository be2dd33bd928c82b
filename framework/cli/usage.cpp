#include "cli/usage.hpp"

namespace brickyard::fw::cli {

const char* const kUsage = R"(brickyard — plugin-based autonomy framework

usage:
  brickyard run GRAPH.json [options]       run a graph
  brickyard validate GRAPH.json [options]  check everything, start nothing
  brickyard plugins [NAME] [--json]        list the plugins found and their manifests (NAME: that one only)
  brickyard graph GRAPH.json --dot         print the graph for Graphviz
  brickyard report RUN_DIR                 write RUN_DIR/report.html from a run's recording
  brickyard bag info RECORDING [--json]    a recording's clock, span and topics (types, counts, rates,
                                           bytes)
  brickyard bag play RECORDING             republish its topics over DDS at the recorded times
                                           (--rate X, --only NODE.PORT,..., --domain N); a ROS 2 bag
                                           of your own with --map FILE: its topics onto wires (docs/ros2.md)
  brickyard capture info FILE [--json]     a sensor's capture: a pcap's UDP datagrams by port, span, rate
                                           and refusals (--metadata OUSTER.json: its lidar port's packets
                                           decoded into frames; --port P: that port's), or a GNSS log's
                                           OEM7 logs or NMEA sentences by type, refusals and time span
  brickyard capture play FILE --to udp://HOST:PORT
                                           send it again at its recorded pace: a pcap's UDP payloads,
                                           a GNSS log's bytes by its logs' times (--rate R, 0 as fast as
                                           possible; --port P: only a pcap's datagrams to P; --loop until
                                           Ctrl-C). It sends to --to only, any host named there (tcp://
                                           and serial:// sinks too; docs/drivers.md)
  brickyard map build RECORDING --out DIR  a track file and a point map from a recorded drive:
                                           DIR/track.csv, DIR/map.pcd, DIR/summary.json
                                           (configs/map_build.json; docs/mapping.md)
  brickyard topic list [--domain N]        the wires of graphs running on domain N, over DDS (listens
                                           --duration S, 2 s by default)
  brickyard topic echo NODE.PORT           its samples as JSON lines (--count N, --duration S)
  brickyard topic hz NODE.PORT             its rate, a line a second (--count N, --duration S)
  brickyard security init GRAPH --out DIR  DDS security for the graph: a CA, an identity per process
                                           and one to observe, signed governance and permissions from
                                           its wires (--protect encrypt|sign, --days N; docs/security.md)
                                           topic and bag play take --security DIR (bag play --identity P)
  brickyard ros2 msgs --out DIR            the SDK's messages as a ROS 2 message package (package.xml,
                                           CMakeLists.txt, msg/*.msg: the same CDR; docs/ros2.md)
  brickyard ros2 idl --out FILE            the same in IDL as ROS 2's DDS middlewares name it on the
                                           wire, for a DDS program without ROS 2 (Cyclone DDS's idlc)
  brickyard new-plugin NAME --dir DIR [--role ROLE]
                                           scaffold a plugin project from the SDK template (or from
                                           the template of a role: a plugin that plays it, docs/roles.md)
  brickyard --version

options:
  --duration S         stop after S seconds (sim or real clock); overrides clock.duration_s
  --set NODE.PARAM=V   override a parameter (V is JSON, or else a string); repeatable
  --arg NAME=V         give one of the graph's named arguments ("args", used as ${NAME}) a value;
                       repeatable
  --seed N             seed of every random source (default 0)
  --process NAME       run only the nodes of process NAME; other processes meet over DDS.
                       Without it, a real-clock graph whose nodes name several processes is
                       supervised: each process a child, watched, restarted by the graph's
                       "processes" policies (docs/reliability.md)
  --one-process        run every node of such a graph in this one process instead
  --domain N           DDS domain id; overrides transport.domain
  --plugin-path DIR    search DIR for plugin libraries first (its plugins override those of
                       the same name found later); repeatable
  --quiet              only warnings and errors
  --progress S         a progress line every S seconds (default: 0.25 on a terminal, one
                       updating line; 5 otherwise, plain lines); 0: none
  --out DIR            write DIR/summary.json, and (unless --no-report) record the run's wires
                       but its point clouds into DIR/recording.mcap and write DIR/report.html
  --no-report          with --out: the summary alone (also the case with --process)
  --record FILE        record every wire's samples into FILE: MCAP, or SQLite when FILE ends in
                       .db3 (docs/recording.md)
  --record-compression zstd|lz4|none   the MCAP chunks' (default zstd)
  --record-scene on|off                the scene in Foxglove's schemas (/tf, /scene/*) into an MCAP
                       recording too, as the live view draws it (default: on, but with
                       --record-only; docs/recording.md)
  --record-profile brickyard|ros2      the MCAP file's names: ours (omgidl schemas, default) or a ROS 2
                       bag's (ros2msg schemas, topics /brickyard/NODE/PORT; docs/recording.md)
  --record-only P,...  record only the topics NODE.PORT matching these patterns ('*' any)
  --record-cloud-precision M   record point clouds compact, each coordinate to M metres
                       (0 < M <= 0.1; about 4x smaller; docs/recording.md)
  --live PORT          serve the run to Foxglove (WebSocket, foxglove.websocket.v1) on
                       127.0.0.1:PORT: every wire as a channel (docs/live.md)
  --live-address A     bind the live server to address A instead (opt-in: 0.0.0.0 is every
                       interface)
  --live-cloud-hz X    send each point-cloud channel at most X clouds a second of wall time
                       (default 20, a display's rate; 0: every cloud)
  --pace X             sim clock: run at most X times real time (0.001 to 1e6), so a person can watch
  --threads N          sim clock: step nodes that cannot see each other on N threads (default:
                       the machine's cores, at most 4); the run is the same on any number
  --profile            time each node's steps on the wall clock: a table at the end, sorted by
                       time, and "step_wall_s" per node in the summary (docs/performance.md)

exit codes: 0 success, 1 the run failed, 2 invalid input
)";

}  // namespace brickyard::fw::cli
