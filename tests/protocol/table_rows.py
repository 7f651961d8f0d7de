"""The message table as table_dump prints it (the compiled table, not protogen's documents).

Types are decoded from their names (u8..i32: signedness from the letter, width from the number),
scales to the shortest decimal that reads back as the same double (Python's repr), so that the
tests compare the documents with exact decimals derived here, not with protogen's arithmetic."""
import subprocess
from decimal import Decimal

# The broadcast stops are in the DBC as messages of their own at node 0 (protocol.md: node 0
# addresses every controller, only ESTOP and STOP honour it).
BROADCAST = {"ESTOP": "ESTOP_ALL", "STOP": "STOP_ALL"}


class Field:
    def __init__(self, name, type_, offset, lo, hi, scale, unit, doc):
        self.name, self.type, self.unit, self.doc = name, type_, unit, doc
        self.flags = []  # (bit number, name, doc) of a field of bits
        self.offset, self.min, self.max = int(offset), int(lo), int(hi)
        self.scale = float(scale)
        self.scale_dec = Decimal(repr(self.scale))
        if type_[0] not in "ui" or type_[1:] not in ("8", "16", "24", "32"):
            raise ValueError(f"unknown field type {type_!r} of {name}")
        self.signed = type_[0] == "i"
        self.bits = int(type_[1:])

    def meaning(self):
        """What the documents say of the field: its doc, and each bit's number, name and doc (protogen's
        words, written out here from the table's entries)."""
        return self.doc + "".join(f"{':' if i == 0 else ';'} bit {bit} {name} ({doc})"
                                  for i, (bit, name, doc) in enumerate(self.flags))

    def type_range(self):
        if self.signed:
            return -(1 << (self.bits - 1)), (1 << (self.bits - 1)) - 1
        return 0, (1 << self.bits) - 1


class Message:
    def __init__(self, name, function, dlc, doc):
        self.name, self.doc = name, doc
        self.function, self.dlc = int(function), int(dlc)
        self.fields = []

    def can_id(self, node):
        return self.function << 4 | node


def load(dumper):
    """Messages in table order."""
    out = subprocess.run([dumper], capture_output=True, text=True, check=True).stdout
    messages = {}
    for number, line in enumerate(out.splitlines(), 1):
        cols = line.split("\t")
        if cols[0] == "M" and len(cols) == 5:
            messages[cols[1]] = Message(*cols[1:])
        elif cols[0] == "F" and len(cols) == 10 and cols[1] in messages:
            messages[cols[1]].fields.append(Field(*cols[2:]))
        elif (cols[0] == "B" and len(cols) == 6 and cols[1] in messages and messages[cols[1]].fields
              and messages[cols[1]].fields[-1].name == cols[2]):
            mask = int(cols[3])
            if mask <= 0 or mask & (mask - 1):
                raise ValueError(f"table_dump line {number}: flag {cols[4]}'s mask {mask} is not one bit")
            messages[cols[1]].fields[-1].flags.append((mask.bit_length() - 1, cols[4], cols[5]))
        else:
            raise ValueError(f"table_dump line {number}: cannot read {line!r}")
    if not messages:
        raise ValueError("table_dump printed no messages")
    return list(messages.values())
