"""Locating a jump in mu, shared by find_jump, trace and the accuracy study: bisection with
ITP steps, certification, the prescan and JumpSearch. Ask/tell state machines: no I/O."""
