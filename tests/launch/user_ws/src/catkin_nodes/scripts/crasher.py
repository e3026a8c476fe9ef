#!/usr/bin/env python3
def divide(a, b):
    return a / b


print("crasher: about to divide", flush=True)
divide(1, 0)
