// lcm-spy itself, live: starts its window (lcm.spy.Spy, the class tools/spy runs) on an LCM URL, says
// "spy ready", and when its standard input closes (the run is over) prints lcm-spy's own channel
// table: per channel the class it matched by fingerprint, messages received, decode errors, and
// whether its last message decoded into that class. Run under xvfb-run when there is no display.
//
// Usage: java SpyProbe URL   -> lines "live CHANNEL CLASS|- received=N errors=N decoded=true|false"
import java.lang.reflect.Field;
import java.util.ArrayList;
import java.util.List;

import lcm.spy.ChannelData;
import lcm.spy.Spy;

public class SpyProbe {
    @SuppressWarnings("unchecked")  // Spy.channelList is an ArrayList<ChannelData>
    public static void main(String[] args) throws Exception {
        if (args.length != 1) {
            System.err.println("usage: SpyProbe URL");
            System.exit(2);
        }
        Spy spy = new Spy(args[0]);
        System.out.println("spy ready");
        System.out.flush();
        while (System.in.read() >= 0) {
            // until the test closes our input
        }
        Field field = Spy.class.getDeclaredField("channelList");  // package-private: no public accessor
        field.setAccessible(true);
        List<ChannelData> channels;
        synchronized (spy) {
            channels = new ArrayList<>((List<ChannelData>) field.get(spy));
        }
        for (ChannelData cd : channels) {
            boolean decoded = cd.cls != null && cd.cls.isInstance(cd.last);
            System.out.println("live " + cd.name + " " + (cd.cls == null ? "-" : cd.cls.getName()) + " received="
                               + cd.nreceived + " errors=" + cd.nerrors + " decoded=" + decoded);
        }
        System.out.flush();
        System.exit(0);
    }
}
