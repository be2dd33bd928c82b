# Sourced by tests of supervised runs: child_pid PROCESS LOG prints the pid of the supervised
# child PROCESS once the supervisor's LOG says it started and the child says it is running
# (20 s at most); nothing when it never did.
child_pid() {
  local name=$1 log=$2 pid=""
  for _ in $(seq 1 200); do
    pid=$(sed -n "s/.*process '$name' started (pid \([0-9]*\)).*/\1/p" "$log" | head -n 1)
    [ -n "$pid" ] && grep -q "\[$name\] \[brickyard\] running" "$log" && break
    sleep 0.1
  done
  echo "$pid"
}
