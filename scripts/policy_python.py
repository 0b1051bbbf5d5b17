#!/usr/bin/env python3
"""Evaluate a rodlab policy file (rodlab.policy/1, docs/learning.md "Policy file") in Python.

    policy_python.py POLICY INPUTS OUT [--torch-resave RESAVED]

INPUTS: a JSON list of observations. OUT gets {"python": [actions...], "torch": [...] or null}:
the network's outputs by plain Python (json and math only, no numpy), and by PyTorch in
float64 when torch is importable. With --torch-resave and torch present, the network is loaded
into a torch.nn.Sequential and written back from its state_dict into RESAVED (the rest of the
policy file unchanged): the round trip through torch that tests/learning/test_policy.cpp
checks bit for bit.
"""
import json
import math
import sys


def act(name, z):
    if name == "tanh":
        return [math.tanh(v) for v in z]
    if name == "relu":
        return [max(v, 0.0) for v in z]
    return list(z)


def evaluate(net, x):
    layers = net["layers"]
    names = [net["hidden_activation"]] * (len(layers) - 1) + [net["output_activation"]]
    for layer, name in zip(layers, names):
        x = act(name, [sum(w * v for w, v in zip(row, x)) + b
                       for row, b in zip(layer["W"], layer["b"])])
    return x


def torch_model(net):
    import torch
    modules = []
    names = [net["hidden_activation"]] * (len(net["layers"]) - 1) + [net["output_activation"]]
    for layer, name in zip(net["layers"], names):
        linear = torch.nn.Linear(len(layer["W"][0]), len(layer["W"]), dtype=torch.float64)
        with torch.no_grad():
            linear.weight.copy_(torch.tensor(layer["W"], dtype=torch.float64))
            linear.bias.copy_(torch.tensor(layer["b"], dtype=torch.float64))
        modules.append(linear)
        if name == "tanh":
            modules.append(torch.nn.Tanh())
        elif name == "relu":
            modules.append(torch.nn.ReLU())
    return torch.nn.Sequential(*modules)


def main(argv):
    policy = json.load(open(argv[1]))
    inputs = json.load(open(argv[2]))
    net = policy["network"]
    out = {"python": [evaluate(net, x) for x in inputs], "torch": None}
    try:
        import torch
    except ImportError:
        torch = None
    if torch is not None:
        model = torch_model(net)
        with torch.no_grad():
            out["torch"] = model(torch.tensor(inputs, dtype=torch.float64)).tolist()
        if "--torch-resave" in argv:
            state = model.state_dict()
            linears = [k[:-len(".weight")] for k in state if k.endswith(".weight")]
            for layer, key in zip(net["layers"], linears):
                layer["W"] = state[key + ".weight"].tolist()
                layer["b"] = state[key + ".bias"].tolist()
            with open(argv[argv.index("--torch-resave") + 1], "w") as f:
                json.dump(policy, f)
    with open(argv[3], "w") as f:
        json.dump(out, f)


if __name__ == "__main__":
    main(sys.argv)
