// Decodes every event of an LCM log with the ugv classes found in a jar, finding each class
// by its fingerprint as lcm-spy does, and prints: channel TAB class TAB field=value ...
// Usage: java -cp lcm.jar:ugv_lcmtypes.jar:ugv_decode_all.jar DecodeAll LOG TYPES_JAR
import java.io.DataInputStream;
import java.io.ByteArrayInputStream;
import java.lang.reflect.Field;
import java.lang.reflect.Modifier;
import java.util.Arrays;
import java.util.Enumeration;
import java.util.HashMap;
import java.util.Map;
import java.util.jar.JarEntry;
import java.util.jar.JarFile;
import lcm.logging.Log;

public class DecodeAll {
    public static void main(String[] args) throws Exception {
        Map<Long, Class<?>> byFingerprint = new HashMap<>();
        try (JarFile jar = new JarFile(args[1])) {
            for (Enumeration<JarEntry> e = jar.entries(); e.hasMoreElements();) {
                String name = e.nextElement().getName();
                if (!name.endsWith(".class") || name.contains("$")) continue;
                Class<?> c = Class.forName(name.replace('/', '.').replace(".class", ""));
                try {
                    byFingerprint.put(c.getField("LCM_FINGERPRINT").getLong(null), c);
                } catch (NoSuchFieldException ignored) {
                }
            }
        }
        Log log = new Log(args[0], "r");
        while (true) {
            Log.Event ev;
            try {
                ev = log.readNext();
            } catch (java.io.EOFException end) {
                break;
            }
            long fp = new DataInputStream(new ByteArrayInputStream(ev.data)).readLong();
            Class<?> c = byFingerprint.get(fp);
            if (c == null) {
                System.out.println(ev.channel + "\tUNKNOWN");
                continue;
            }
            Object msg = c.getConstructor(byte[].class).newInstance((Object) ev.data);
            StringBuilder line = new StringBuilder(ev.channel + "\t" + c.getName());
            for (Field f : c.getFields()) {
                if (Modifier.isStatic(f.getModifiers())) continue;
                Object v = f.get(msg);
                String s;
                if (v instanceof float[]) s = Arrays.toString((float[]) v);
                else if (v instanceof double[]) s = Arrays.toString((double[]) v);
                else if (v instanceof byte[]) s = Arrays.toString((byte[]) v);
                else if (v instanceof int[]) s = Arrays.toString((int[]) v);
                else if (v instanceof long[]) s = Arrays.toString((long[]) v);
                else if (v instanceof Object[]) s = Arrays.toString((Object[]) v);
                else s = String.valueOf(v);
                line.append("\t").append(f.getName()).append("=").append(s);
            }
            System.out.println(line);
        }
    }
}
