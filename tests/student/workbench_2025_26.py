# A student's AppWorkbench.py in the style of the 2025-26 handout of Practice 2, Part I,
# with Assignment 2.1 done: the integral of cos over the hemisphere estimated with uniform
# samples, the handout's collect_samples, the student's compute_estimate_cmc (summing
# RGBColor values from BLACK), the handout's set-up and plot, seeded to reproduce its
# numbers. tests/test_workbench.py runs it unchanged, without a screen, from a folder
# outside the repository.
from PyRT_Common import *
import random

random.seed(1)


def collect_samples(function_list, sample_pos_):
    sample_values = []
    for i in range(len(sample_pos_)):
        val = 1
        for j in range(len(function_list)):
            val *= function_list[j].eval(sample_pos_[i])
        sample_values.append(RGBColor(val, 0, 0))  # for convenience, we'll only use the red channel
    return sample_values


def compute_estimate_cmc(sample_prob_, sample_values_):
    estimate = BLACK
    for i in range(len(sample_values_)):
        estimate += sample_values_[i] / sample_prob_[i]
    return estimate.r / len(sample_values_)


# STEP 0: the name of the methods, and their marker for the plot
methods_label = [('MC', 'o')]
n_methods = len(methods_label)

# STEP 1: the integrand, L_i * brdf * cos
l_i = Constant(1)
kd = 1
brdf = Constant(kd)
cosine_term = CosineLobe(1)
integrand = [l_i, brdf, cosine_term]

# STEP 2: the pdf
uniform_pdf = UniformPDF()

ground_truth = cosine_term.get_integral()  # L_i = 1 and BRDF = 1
print('Ground truth: ' + str(ground_truth))

# STEP 3: the experimental set-up
ns_min = 20
ns_max = 101
ns_step = 20
ns_vector = np.arange(start=ns_min, stop=ns_max, step=ns_step)
n_estimates = 200
n_samples_count = len(ns_vector)

results = np.zeros((n_samples_count, n_methods))

for k, ns in enumerate(ns_vector):
    print(f'Computing estimates using {ns} samples')
    error = 0
    for i in range(n_estimates):
        sample_set, sample_prob = sample_set_hemisphere(ns, uniform_pdf)
        sample_values = collect_samples(integrand, sample_set)
        estimate = compute_estimate_cmc(sample_prob, sample_values)
        error += abs(ground_truth - estimate)
    results[k, 0] = error / n_estimates

for k in range(n_samples_count):
    print('Average error with ' + str(ns_vector[k]) + ' samples: ' + str(results[k, 0]))

for k in range(len(methods_label)):
    method = methods_label[k]
    plt.plot(ns_vector, results[:, k], label=method[0], marker=method[1])

plt.legend()
plt.savefig('workbench.png')
plt.show()
