"""Speaking to a running controller process: its socket and heartbeat, the Module-Task proxies
the executive drives, the mission's automaton stepped in it."""
