"""A hidraw node for umockdev-run, made from a hid-tools recording: the sysfs side (the hidraw
node, its HID device with the recording's descriptor, name and ids, the USB interface and
device hidapi looks up), the ioctl answers hid_open_path asks for (HIDIOCGRDESCSIZE,
HIDIOCGRDESC), and a read script replaying reports (one `r` line a report, `pace_ms` apart so
that no two merge in the byte stream; the first after `first_ms`, counted from the open)."""
import pathlib

NODE = "/dev/hidraw0"
HID_MAX_DESCRIPTOR_SIZE = 4096


def read_recording(path):
    """(descriptor bytes, name, (bus, vid, pid), [report bytes]) of a one-device recording"""
    desc, name, ids, reports = None, None, None, []
    for line in pathlib.Path(path).read_text().splitlines():
        tag, _, rest = line.partition(": ")
        if tag == "R":
            n, *hexes = rest.split()
            desc = bytes(int(h, 16) for h in hexes)
            assert len(desc) == int(n)
        elif tag == "N":
            name = rest
        elif tag == "I":
            ids = tuple(int(x, 16) for x in rest.split())
        elif tag == "E":
            _, n, *hexes = rest.split()
            reports.append(bytes(int(h, 16) for h in hexes))
            assert len(reports[-1]) == int(n)
    return desc, name, ids, reports


def script_bytes(data):
    """umockdev's script escaping: bytes below 32 as ^ and b + 64, '^' as ^`"""
    out = bytearray()
    for b in data:
        if b < 32:
            out += bytes([ord("^"), b + 64])
        elif b == ord("^"):
            out += b"^`"
        else:
            out.append(b)
    return bytes(out)


def write_mock(d, desc, name, ids, reports, first_ms=150, pace_ms=150):
    """the .umockdev, .ioctl and .script files in folder d; returns their paths"""
    d = pathlib.Path(d)
    bus, vid, pid = ids
    usb = "/devices/pci0000:00/0000:00:01.2/usb1/1-1"
    intf = usb + "/1-1:1.0"
    hid = intf + "/%04X:%04X:%04X.0001" % (bus, vid, pid)
    (d / "hidmouse.umockdev").write_text("\n".join([
        "P: " + hid + "/hidraw/hidraw0",
        "N: hidraw0",
        "E: DEVNAME=" + NODE,
        "E: MAJOR=240",
        "E: MINOR=0",
        "E: SUBSYSTEM=hidraw",
        "A: dev=240:0\\n",
        "L: device=../../../%04X:%04X:%04X.0001" % (bus, vid, pid),
        "",
        "P: " + hid,
        "E: DRIVER=hid-generic",
        "E: HID_ID=%04X:%08X:%08X" % (bus, vid, pid),
        "E: HID_NAME=" + name,
        "E: HID_PHYS=usb-0000:00:01.2-1/input0",
        "E: HID_UNIQ=",
        "E: MODALIAS=hid:b%04Xg0001v%08Xp%08X" % (bus, vid, pid),
        "E: SUBSYSTEM=hid",
        "H: report_descriptor=" + desc.hex().upper(),
        "",
        "P: " + intf,
        "E: DEVTYPE=usb_interface",
        "E: DRIVER=usbhid",
        "E: SUBSYSTEM=usb",
        "A: bInterfaceNumber=00\\n",
        "A: bInterfaceClass=03\\n",
        "",
        "P: " + usb,
        "E: DEVTYPE=usb_device",
        "E: DRIVER=usb",
        "E: SUBSYSTEM=usb",
        "A: idVendor=%04x\\n" % vid,
        "A: idProduct=%04x\\n" % pid,
        "A: manufacturer=QEMU\\n",
        "A: product=QEMU USB Mouse\\n",
        "A: bcdDevice=0000\\n",
        "",
    ]))
    # hid_open_path asks the node for its descriptor: struct hidraw_report_descriptor
    size = len(desc).to_bytes(4, "little")
    full = size + desc + bytes(HID_MAX_DESCRIPTOR_SIZE - len(desc))
    (d / "hidmouse.ioctl").write_text("@DEV %s\nHIDIOCGRDESCSIZE 0 %s\nHIDIOCGRDESC 0 %s\n" % (
        NODE, size.hex().upper(), full.hex().upper()))
    with open(d / "hidmouse.script", "wb") as f:
        for i, r in enumerate(reports):
            f.write(b"r %d " % (first_ms if i == 0 else pace_ms) + script_bytes(r) + b"\n")
    return d / "hidmouse.umockdev", d / "hidmouse.ioctl", d / "hidmouse.script"


def umockdev_args(paths):
    """umockdev-run's arguments for the node, before its `--`"""
    dev, ioctl, script = paths
    return ["-d", str(dev), "-i", "%s=%s" % (NODE, ioctl), "-s", "%s=%s" % (NODE, script)]
