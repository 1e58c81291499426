// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/button.strl
// (Esterel v5 source) with its published trace test/button.in / test/button.out (commit ff9a3850).
// The BUTTON module of Berry's wristwatch.
mission BUTTON {
    input UL, UR, LL, LR;
    relation UL # UR # LL # LR;
    output WATCH_MODE_COMMAND, ENTER_SET_WATCH_MODE_COMMAND, SET_WATCH_COMMAND,
           NEXT_WATCH_TIME_POSITION_COMMAND, EXIT_SET_WATCH_MODE_COMMAND,
           TOGGLE_24H_MODE_COMMAND, TOGGLE_CHIME_COMMAND, STOPWATCH_MODE_COMMAND,
           START_STOP_COMMAND, LAP_COMMAND, ALARM_MODE_COMMAND, ENTER_SET_ALARM_MODE_COMMAND,
           SET_ALARM_COMMAND, NEXT_ALARM_TIME_POSITION_COMMAND, EXIT_SET_ALARM_MODE_COMMAND,
           TOGGLE_ALARM_COMMAND, STOP_ALARM_BEEP_COMMAND;
    par {
        loop {
            emit WATCH_MODE_COMMAND;
            trap WATCH_AND_SET_WATCH_MODE {
                loop {
                    abort {
                        par { await LL; exit WATCH_AND_SET_WATCH_MODE; }
                        || { every LR { emit TOGGLE_24H_MODE_COMMAND; } }
                    } when UL;
                    emit ENTER_SET_WATCH_MODE_COMMAND;
                    abort {
                        par { every LL { emit NEXT_WATCH_TIME_POSITION_COMMAND; } }
                        || { every LR { emit SET_WATCH_COMMAND; } }
                    } when UL;
                    emit EXIT_SET_WATCH_MODE_COMMAND;
                }
            }
            emit STOPWATCH_MODE_COMMAND;
            abort {
                par { every LR { emit START_STOP_COMMAND; } }
                || { every UR { emit LAP_COMMAND; } }
            } when LL;
            trap ALARM_AND_SET_ALARM_MODE {
                emit ALARM_MODE_COMMAND;
                loop {
                    abort {
                        par { await LL; exit ALARM_AND_SET_ALARM_MODE; }
                        || { every LR { emit TOGGLE_CHIME_COMMAND; } }
                        || { every UR { emit TOGGLE_ALARM_COMMAND; } }
                    } when UL;
                    emit ENTER_SET_ALARM_MODE_COMMAND;
                    abort {
                        par { every LL { emit NEXT_ALARM_TIME_POSITION_COMMAND; } }
                        || { every LR { emit SET_ALARM_COMMAND; } }
                    } when UL;
                    emit EXIT_SET_ALARM_MODE_COMMAND;
                }
            }
        }
    } || {
        every UR { emit STOP_ALARM_BEEP_COMMAND; }
    }
}
