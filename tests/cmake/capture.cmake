# `brickyard capture info | play` (docs/drivers.md, "Captures: info and play"): the shipped
# captures inspected and played. Included by tests/CMakeLists.txt.
set(CAPTURE_DATA ${PROJECT_SOURCE_DIR}/data)
set(LIDAR_PACKETS ${CAPTURE_DATA}/lidar_packets)
set(OS1_LB ${LIDAR_PACKETS}/OS-1-128_v2.3.0_1024x10_lb_n3.pcap)
set(BESTPOS ${CAPTURE_DATA}/gnss/novatel_BESTPOS.GPS)

# What a person reads; the numbers of every capture, checked against the files read on their own.
cli_test(capture_info_ouster 0 " 7502 +192 +1622016 .*\n 7503 +30 +1440 .*packets +192 fed, 192 decoded, 0 refused.*frames +3 complete, 0 incomplete"
         capture info ${OS1_LB} --metadata ${LIDAR_PACKETS}/OS-1-128_v2.3.0_1024x10.json)
cli_test(capture_info_gnss 0 "NovAtel OEM7.*BESTPOSA +1000\nrefused +0 .*GPS week 1984 450849.500 s" capture info ${BESTPOS})
add_test(NAME cli.capture_info_numbers COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/capture_info.sh ${BY} ${CAPTURE_DATA} ${RUNS}/capture_info)
# Played to the Ouster driver and to a receiver over UDP on loopback, and stopped by signals.
by_next_domain(d)
add_test(NAME cli.capture_play COMMAND ${NETNS} ${CMAKE_CURRENT_SOURCE_DIR}/cli/capture_play.sh ${BY} ${CAPTURE_DATA}
         ${CMAKE_CURRENT_SOURCE_DIR}/graphs/capture ${d} ${RUNS}/capture_play)
set_tests_properties(cli.capture_play PROPERTIES TIMEOUT 120)
# A receiver that reboots: the driver opens its TCP port again and reads on (docs/drivers-transports.md).
by_next_domain(d)
add_test(NAME cli.gnss_reopen COMMAND ${NETNS} ${CMAKE_CURRENT_SOURCE_DIR}/cli/gnss_reopen.sh ${BY}
         ${CMAKE_CURRENT_SOURCE_DIR}/graphs/capture ${d} ${RUNS}/gnss_reopen)
set_tests_properties(cli.gnss_reopen PROPERTIES TIMEOUT 120)

# Bad input: exit 2, the culprit named, nothing read forever and nothing sent.
function(capture_bad name regex)
  add_test(NAME bad_input.capture_${name} COMMAND ${EXPECT} 2 "${regex}" -- ${BY} capture ${ARGN})
  set_tests_properties(bad_input.capture_${name} PROPERTIES TIMEOUT 30)
endfunction()
capture_bad(missing "error: .*/nowhere.pcap: cannot be opened \\(No such file or directory\\)" info ${RUNS}/nowhere.pcap)
capture_bad(device "error: /dev/zero: not a regular file" info /dev/zero)
capture_bad(metadata_missing "error: .*/nowhere.json: cannot be opened" info ${OS1_LB} --metadata ${RUNS}/nowhere.json)
capture_bad(metadata_malformed "error: .*/malformed.json: metadata: not a JSON object" info ${OS1_LB} --metadata ${BAD}/malformed.json)
capture_bad(metadata_of_a_log "error: --metadata: decodes an Ouster pcap's packets; .*novatel_BESTPOS.GPS is a GNSS log" info ${BESTPOS} --metadata ${LIDAR_PACKETS}/crc_test.json)
capture_bad(no_command "error: capture: needs a command \\(brickyard capture info FILE")
capture_bad(unknown_command "error: capture frob: unknown capture command" frob ${BESTPOS})
capture_bad(to_missing "error: capture play: needs --to udp://HOST:PORT" play ${BESTPOS})
capture_bad(to_port "error: --to: source 'udp://127.0.0.1:70000': port 70000 out of 1..65535" play ${BESTPOS} --to udp://127.0.0.1:70000)
capture_bad(to_host_name "error: --to: .*host 'localhost' is not an IPv4 address" play ${BESTPOS} --to udp://localhost:7502)
capture_bad(to_not_a_sink "error: --to: file:///tmp/by_capture: cannot be sent to: only udp, tcp and serial are sinks" play ${BESTPOS} --to file:///tmp/by_capture)
capture_bad(rate_negative "error: --rate: expected a factor of the recorded pace, 0 \\(as fast as possible\\) or from 0.001 to 1e6" play ${BESTPOS} --to udp://127.0.0.1:9 --rate -1)
capture_bad(rate_tiny "error: --rate: expected a factor of the recorded pace, 0 \\(as fast as possible\\) or from 0.001 to 1e6" play ${BESTPOS} --to udp://127.0.0.1:9 --rate 1e-300)
capture_bad(rate_not_a_number "error: --rate fast: expected a number" play ${BESTPOS} --to udp://127.0.0.1:9 --rate fast)
capture_bad(port_of_a_log "error: --port: selects a pcap's datagrams; .*novatel_BESTPOS.GPS is a GNSS log" play ${BESTPOS} --to udp://127.0.0.1:9 --port 7502)
capture_bad(port_absent "error: .*crc_test.pcap: no UDP datagram to port 1234" play ${LIDAR_PACKETS}/crc_test.pcap --to udp://127.0.0.1:9 --port 1234)
capture_bad(nothing_to_pace "error: .*nmea_sync_error.txt: no OEM7 log or NMEA sentence in it to pace the bytes by" play ${CAPTURE_DATA}/gnss/nmea_sync_error.txt --to udp://127.0.0.1:9)
# A FIFO (a read would wait for a writer forever) and a pcapng file, made where the test runs.
add_test(NAME bad_input.capture_fifo COMMAND sh -c "mkdir -p ${RUNS} && rm -f ${RUNS}/capture.fifo && mkfifo ${RUNS}/capture.fifo && exec \"$0\" \"$@\""
  ${EXPECT} 2 "error: .*/capture.fifo: not a regular file" -- ${BY} capture play ${RUNS}/capture.fifo --to udp://127.0.0.1:9)
add_test(NAME bad_input.capture_pcapng COMMAND sh -c "mkdir -p ${RUNS} && printf '\\012\\015\\015\\012\\034\\0\\0\\0\\115\\074\\053\\032\\001\\0\\0\\0\\377\\377\\377\\377\\377\\377\\377\\377\\034\\0\\0\\0' > ${RUNS}/capture.pcapng && exec \"$0\" \"$@\""
  ${EXPECT} 2 "error: .*/capture.pcapng: a pcapng file: only classic pcap is read \\(editcap -F pcap converts\\)" -- ${BY} capture info ${RUNS}/capture.pcapng)
# The same FIFO for a recording (bag info and bag play waited for a writer forever: issue 44).
add_test(NAME bad_input.bag_info_fifo COMMAND sh -c "mkdir -p ${RUNS} && rm -f ${RUNS}/bag.fifo && mkfifo ${RUNS}/bag.fifo && exec \"$0\" \"$@\""
  ${EXPECT} 2 "error: .*/bag.fifo: not a regular file" -- ${BY} bag info ${RUNS}/bag.fifo)
add_test(NAME bad_input.bag_play_fifo COMMAND sh -c "mkdir -p ${RUNS} && rm -f ${RUNS}/bag_play.fifo && mkfifo ${RUNS}/bag_play.fifo && exec \"$0\" \"$@\""
  ${EXPECT} 2 "error: .*/bag_play.fifo: not a regular file" -- ${BY} bag play ${RUNS}/bag_play.fifo)
set_tests_properties(bad_input.capture_fifo bad_input.capture_pcapng bad_input.bag_info_fifo bad_input.bag_play_fifo PROPERTIES TIMEOUT 30)
