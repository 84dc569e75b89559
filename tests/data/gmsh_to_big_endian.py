#!/usr/bin/python3
"""Rewrites a little-endian binary Gmsh mesh (format 2.2 or 4.1, as gmsh -bin
writes it on x86) in big-endian byte order, as gmsh writes it on a big-endian
machine: every binary int, size_t and double is byte-swapped, the text parts
are copied. Only the sections a mesh needs are understood ($MeshFormat,
$PhysicalNames, $Entities, $Nodes, $Elements); any other is an error.

    /usr/bin/python3 gmsh_to_big_endian.py IN.msh OUT.msh
"""
import struct
import sys

# Nodes per element for the Gmsh element types 1..31.
NODES = [2, 3, 4, 4, 8, 6, 5, 3, 6, 9, 10, 27, 18, 14, 1, 8, 20, 15, 13, 9, 10, 12, 15, 15, 21, 4, 5, 6,
         20, 35, 56]


class Converter:
    def __init__(self, data):
        self.data = data
        self.pos = 0
        self.out = bytearray()

    def text_line(self):
        end = self.data.index(b"\n", self.pos) + 1
        line = self.data[self.pos:end]
        self.out += line
        self.pos = end
        return line.decode("ascii").strip()

    def swap(self, fmt):
        size = struct.calcsize("<" + fmt)
        values = struct.unpack_from("<" + fmt, self.data, self.pos)
        self.out += struct.pack(">" + fmt, *values)
        self.pos += size
        return values

    def int(self):
        return self.swap("i")[0]

    def size(self):
        return self.swap("Q")[0]

    def convert(self):
        assert self.text_line() == "$MeshFormat"
        version, file_type, data_size = self.text_line().split()
        assert file_type == "1" and data_size == "8", "expected a binary file with data size 8"
        assert self.int() == 1, "expected a little-endian file"
        v4 = version.startswith("4")
        self.text_line()  # the newline after the binary 1
        assert self.text_line() == "$EndMeshFormat"
        while self.pos < len(self.data):
            section = self.text_line()
            if section == "":
                continue
            if section == "$PhysicalNames":
                for _ in range(int(self.text_line())):
                    self.text_line()
            elif section == "$Entities" and v4:
                counts = [self.size() for _ in range(4)]
                for d in range(4):
                    for _ in range(counts[d]):
                        self.int()
                        self.swap("d" * (3 if d == 0 else 6))
                        self.swap("i" * self.size())
                        if d > 0:
                            self.swap("i" * self.size())
            elif section == "$Nodes" and v4:
                blocks = self.size()
                self.swap("QQQ")
                for _ in range(blocks):
                    dim, _, parametric = self.swap("iii")
                    n = self.size()
                    self.swap("Q" * n)
                    self.swap("d" * (n * (3 + (dim if parametric else 0))))
            elif section == "$Nodes":
                for _ in range(int(self.text_line())):
                    self.swap("iddd")
            elif section == "$Elements" and v4:
                blocks = self.size()
                self.swap("QQQ")
                for _ in range(blocks):
                    _, _, element_type = self.swap("iii")
                    n = self.size()
                    self.swap("Q" * (n * (1 + NODES[element_type - 1])))
            elif section == "$Elements":
                count = int(self.text_line())
                while count > 0:
                    element_type, following, tags = self.swap("iii")
                    self.swap("i" * (following * (1 + tags + NODES[element_type - 1])))
                    count -= following
            else:
                raise SystemExit("unsupported section " + section)
            if section != "$PhysicalNames":
                self.text_line()  # the newline after the binary data
            assert self.text_line() == "$End" + section[1:]
        return bytes(self.out)


def main():
    with open(sys.argv[1], "rb") as f:
        data = f.read()
    with open(sys.argv[2], "wb") as f:
        f.write(Converter(data).convert())


if __name__ == "__main__":
    main()
