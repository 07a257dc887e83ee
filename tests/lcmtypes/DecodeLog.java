// Decodes the sample log written by the C++ side (write_sample_log.cpp) with the project's jar:
// proves the Java classes lcm-spy uses read exactly what the C++ publishers write.
import hapticctrl_lcm.arm_state_t;
import hapticctrl_lcm.cycle_stats_t;
import hapticctrl_lcm.event_t;
import java.io.EOFException;
import java.io.IOException;
import lcm.logging.Log;

public class DecodeLog {
  public static void main(String[] args) throws IOException {
    Log log = new Log(args[0], "r");
    int arms = 0;
    int undecodable = 0;
    double lastX = 0;
    long lastHistogramBin = 0;
    String lastEvent = "";
    while (true) {
      Log.Event ev;
      try {
        ev = log.readNext();
      } catch (EOFException end) {
        break;
      }
      try {
        if (ev.channel.equals("hapticctrl.lab.arm_state")) {
          arm_state_t a = new arm_state_t(ev.data);
          arms++;
          lastX = a.handle_pose[0];
        } else if (ev.channel.equals("hapticctrl.lab.cycle_stats")) {
          lastHistogramBin = new cycle_stats_t(ev.data).wake_histogram[5];
        } else if (ev.channel.equals("hapticctrl.lab.events")) {
          lastEvent = new event_t(ev.data).text;
        }
      } catch (IOException bad) {
        undecodable++;
      }
    }
    System.out.println("arm_states=" + arms + " undecodable=" + undecodable + " last_x=" + lastX
        + " histogram_bin5=" + lastHistogramBin + " last_event=" + lastEvent);
  }
}
