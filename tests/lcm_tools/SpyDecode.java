// Decodes an LCM log the way lcm-spy does: its own type database (lcm.spy.LCMTypeDatabase scans the
// class path, as lcm-spy does at start-up) maps each message's fingerprint to a generated class, which
// decodes it. Checks that every type of the project is found and that every message of the log on a
// known type decodes and re-encodes to the same bytes (nested types included).
//
// Usage: java SpyDecode LOG SAMPLES_CSV PACKAGE TYPE...
//   prints "types found N", "decoded CHANNEL CLASS N", "start ..." (the first START's timing and
//   robot 0's target path); writes every decoded unicycle sample (session, sequence, robot, x, y, read
//   through its nested sample_header_t) to SAMPLES_CSV. Exit 1 on any failure (listed on stderr).
import java.io.EOFException;
import java.io.PrintWriter;
import java.lang.reflect.Field;
import java.nio.ByteBuffer;
import java.util.Arrays;
import java.util.Map;
import java.util.TreeMap;

import lcm.lcm.LCMDataOutputStream;
import lcm.lcm.LCMEncodable;
import lcm.logging.Log;
import lcm.spy.LCMTypeDatabase;

public class SpyDecode {
    public static void main(String[] args) throws Exception {
        if (args.length < 4) {
            System.err.println("usage: SpyDecode LOG SAMPLES_CSV PACKAGE TYPE...");
            System.exit(2);
        }
        int failures = 0;
        LCMTypeDatabase database = new LCMTypeDatabase();
        for (int i = 3; i < args.length; i++) {
            String name = args[2] + "." + args[i];
            Class<?> cls = Class.forName(name);
            long fingerprint = cls.getField("LCM_FINGERPRINT").getLong(null);
            if (!LCMEncodable.class.isAssignableFrom(cls) || database.getClassByFingerprint(fingerprint) != cls) {
                System.err.println("lcm-spy's type database does not map " + name + " by its fingerprint");
                failures++;
            }
        }
        System.out.println("types found " + (args.length - 3 - failures));

        Map<String, Long> decoded = new TreeMap<>();
        Map<String, Long> unknown = new TreeMap<>();
        boolean startPrinted = false;
        Log log = new Log(args[0], "r");
        try (PrintWriter samples = new PrintWriter(args[1])) {
            samples.println("session_id,sequence,robot,x_m,y_m");
            for (;;) {
                Log.Event event;
                try {
                    event = log.readNext();
                } catch (EOFException end) {
                    break;
                }
                // A message shorter than a fingerprint has no type: lcm-spy shows it undecoded too.
                Class<?> cls = event.data.length < 8 ? null
                             : database.getClassByFingerprint(ByteBuffer.wrap(event.data, 0, 8).getLong());
                if (cls == null) {
                    unknown.merge(event.channel, 1L, Long::sum);
                    continue;
                }
                LCMEncodable msg = (LCMEncodable) cls.getConstructor(byte[].class).newInstance((Object) event.data);
                LCMDataOutputStream out = new LCMDataOutputStream();
                msg.encode(out);
                if (!Arrays.equals(out.toByteArray(), event.data)) {
                    System.err.println(event.channel + ": " + cls.getName() + " does not re-encode to its bytes");
                    failures++;
                }
                decoded.merge(event.channel + " " + cls.getName(), 1L, Long::sum);
                if (cls.getSimpleName().equals("unicycle_sample_t")) {
                    Object header = cls.getField("header").get(msg);
                    Class<?> h = header.getClass();
                    double[] position = (double[]) cls.getField("position_m").get(msg);
                    samples.println(h.getField("session_id").getInt(header) + "," + h.getField("sequence").getInt(header)
                                    + "," + h.getField("robot").getByte(header) + "," + position[0] + "," + position[1]);
                } else if (cls.getSimpleName().equals("session_t") && !startPrinted
                           && cls.getField("action").getByte(msg) == cls.getField("ACTION_START").getByte(null)) {
                    startPrinted = true;
                    printStart(cls, msg);
                }
            }
        }
        log.close();
        for (Map.Entry<String, Long> e : decoded.entrySet()) {
            System.out.println("decoded " + e.getKey() + " " + e.getValue());
        }
        for (Map.Entry<String, Long> e : unknown.entrySet()) {
            System.out.println("unknown " + e.getKey() + " " + e.getValue());
        }
        System.exit(failures == 0 ? 0 : 1);
    }

    // The timing and robot 0's target, read through the nested robot_t and path_t.
    static void printStart(Class<?> cls, Object msg) throws Exception {
        Object robot = ((Object[]) cls.getField("robot").get(msg))[0];
        Object path = robot.getClass().getField("target").get(robot);
        StringBuilder line = new StringBuilder("start");
        for (String f : new String[] {"session_id", "epoch_utime", "period_us", "delay_us", "robot_count"}) {
            line.append(' ').append(f).append('=').append(cls.getField(f).get(msg));
        }
        for (Field f : path.getClass().getFields()) {
            if (java.lang.reflect.Modifier.isStatic(f.getModifiers())) {
                continue;
            }
            Object v = f.get(path);
            String text = v instanceof double[] ? Arrays.toString((double[]) v)
                        : v instanceof double[][] ? Arrays.deepToString((double[][]) v) : String.valueOf(v);
            line.append(" target.").append(f.getName()).append('=').append(text.replace(" ", ""));
        }
        System.out.println(line);
    }
}
